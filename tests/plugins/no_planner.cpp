// Fixture plugin: its entry point adds no planner (the registrar.add call was forgotten).
#include "campo/plugin.hpp"

CAMPO_REGISTER_PLANNERS(registrar) { static_cast<void>(registrar); }

#include "grid/search_result.hpp"

namespace campo::grid {

std::string_view to_string(SearchStatus status) {
  switch (status) {
    case SearchStatus::found: return "found";
    case SearchStatus::no_path: return "no_path";
  }
  return "?";
}

}  // namespace campo::grid

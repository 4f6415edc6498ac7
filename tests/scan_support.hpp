#pragma once
// A planner test's own scan handed to a SensorReading without giving up ownership.
#include <memory>

#include "campo/range_scan.hpp"

namespace campo::test_support {

/// A non-owning SensorReading::scan: `scan` must outlive the reading.
inline std::shared_ptr<const RangeScan> borrowed(const RangeScan& scan) {
  return std::shared_ptr<const RangeScan>(std::shared_ptr<const void>(), &scan);
}

}  // namespace campo::test_support

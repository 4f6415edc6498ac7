#pragma once
// One comparison of a peer program as a line of JSON, the form `campo bench peers` reads
// (docs/PERFORMANCE.md, "Peers"): campo's rate and the peer's on the same input, higher
// is faster for both.
#include <cstdio>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

namespace campo::peers {

struct Comparison {
  std::string id;          // stable name across runs, e.g. "lidar/vineyard"
  std::string comparison;  // what is compared, for the table
  double campo = 0.0;      // campo's rate
  double peer = 0.0;       // the peer's rate, same unit
  std::string unit;        // e.g. "rays/s"
  std::string peer_name;   // the peer and how it was used, with its version
  std::string note;        // what was checked to agree
};

// Whether the program was asked for JSON lines (--json) instead of its table rows.
inline bool json_requested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--json") == 0) return true;
  }
  return false;
}

inline void print_json(const Comparison& c) {
  const nlohmann::json line{{"id", c.id},     {"comparison", c.comparison}, {"campo", c.campo}, {"peer", c.peer},
                            {"unit", c.unit}, {"peer_name", c.peer_name},   {"note", c.note}};
  std::printf("%s\n", line.dump().c_str());
}

}  // namespace campo::peers

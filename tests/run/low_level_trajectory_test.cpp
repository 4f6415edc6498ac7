// trajectory.csv's columns of the low-level commands (docs/running.md): only
// in files of vehicles given them, only the kinds given, empty elsewhere.
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campo/episode_record.hpp"
#include "campo/run_record.hpp"

namespace campo {
namespace {

std::vector<std::vector<std::string>> rows(const std::string& csv) {
  std::vector<std::vector<std::string>> out;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (std::size_t end; (end = line.find(',', start)) != std::string::npos; start = end + 1) {
      fields.push_back(line.substr(start, end - start));
    }
    fields.push_back(line.substr(start));
    out.push_back(fields);
  }
  return out;
}

VehicleResult with_commands(const std::vector<Command>& commands) {
  VehicleResult r;
  double t = 0.0;
  for (const Command& c : commands) {
    TrajectorySample s;
    s.time_s = t;
    t += 0.1;
    s.command = c;
    s.actuators = {{"thrust_n", 14.7}};
    r.trajectory.push_back(s);
  }
  return r;
}

std::string field(const std::vector<std::vector<std::string>>& table, std::size_t row, const std::string& name) {
  const auto& header = table.front();
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return table.at(row).at(i);
  }
  ADD_FAILURE() << "no column " << name;
  return "?";
}

TEST(LowLevelTrajectory, FilesWithoutLowLevelCommandsKeepTheirColumns) {
  const auto table = rows(trajectory_csv(with_commands({command::Hold{}, command::GoTo{}})));
  EXPECT_EQ(table.front().back(), "thrust_n");  // the actuators close the header, as before
  EXPECT_EQ(table.front().size(), table.at(1).size());
}

TEST(LowLevelTrajectory, ColumnsOfTheKindsGivenWithTheirValues) {
  const auto table = rows(trajectory_csv(with_commands({command::Hold{},
                                                        command::Velocity{{1.5, -0.5, 0.25}, 0.125},
                                                        command::Rotors{{600.0, 601.0, 602.0, 603.0}}})));
  const auto& header = table.front();
  const std::vector<std::string> expected_tail = {"thrust_n",           "cmd_forward_mps",   "cmd_left_mps",
                                                  "cmd_up_mps",         "cmd_yaw_rate_radps", "cmd_rotor_0_radps",
                                                  "cmd_rotor_1_radps",  "cmd_rotor_2_radps", "cmd_rotor_3_radps"};
  ASSERT_GE(header.size(), expected_tail.size());
  EXPECT_EQ(std::vector<std::string>(header.end() - static_cast<long>(expected_tail.size()), header.end()), expected_tail);
  for (const auto& row : table) EXPECT_EQ(row.size(), header.size());
  EXPECT_EQ(field(table, 1, "command"), "hold");
  EXPECT_EQ(field(table, 1, "cmd_forward_mps"), "");
  EXPECT_EQ(field(table, 2, "command"), "velocity");
  EXPECT_EQ(field(table, 2, "cmd_forward_mps"), "1.5");
  EXPECT_EQ(field(table, 2, "cmd_left_mps"), "-0.5");
  EXPECT_EQ(field(table, 2, "cmd_up_mps"), "0.25");
  EXPECT_EQ(field(table, 2, "cmd_yaw_rate_radps"), "0.125");
  EXPECT_EQ(field(table, 2, "cmd_rotor_0_radps"), "");
  EXPECT_EQ(field(table, 3, "command"), "rotors");
  EXPECT_EQ(field(table, 3, "cmd_rotor_3_radps"), "603");
  EXPECT_EQ(field(table, 3, "cmd_yaw_rate_radps"), "");
}

TEST(LowLevelTrajectory, AttitudeThrustAndWheels) {
  const auto table = rows(trajectory_csv(with_commands({command::AttitudeThrust{0.1, -0.2, 0.3, 15.5},
                                                        command::Wheels{{1.0, 2.0, 3.0, 4.0}}})));
  EXPECT_EQ(field(table, 1, "cmd_roll_rad"), "0.1");
  EXPECT_EQ(field(table, 1, "cmd_pitch_rad"), "-0.2");
  EXPECT_EQ(field(table, 1, "cmd_yaw_rate_radps"), "0.3");
  EXPECT_EQ(field(table, 1, "cmd_thrust_n"), "15.5");
  EXPECT_EQ(field(table, 2, "cmd_front_left_radps"), "1");
  EXPECT_EQ(field(table, 2, "cmd_rear_right_radps"), "4");
  EXPECT_EQ(field(table, 2, "cmd_thrust_n"), "");
  for (const char* absent : {"cmd_forward_mps", "cmd_rotor_0_radps"}) {
    EXPECT_EQ(std::find(table.front().begin(), table.front().end(), absent), table.front().end()) << absent;
  }
}

}  // namespace
}  // namespace campo

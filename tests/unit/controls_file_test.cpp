// Controls files and trajectory output of the tools.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/tools/controls_file.h"
#include "rbsf/tools/trajectory_writer.h"

namespace rbsf::tools {
namespace {

std::string messageOf(const std::string& text, int m) {
  try {
    ControlSchedule::parse(text, m, "c.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ControlsFile, ParsesSegmentsWithCommentsBlanksAndCrlf) {
  const ControlSchedule s = ControlSchedule::parse(
      "# comment\r\n duration , tau_theta,tau_1,tau_2 \r\n\r\n1.5, 2e1 ,-3,+4\r\n"
      "# another\n0.25,0,0,0",
      2, "c.csv");
  ASSERT_EQ(s.segments().size(), 2u);
  EXPECT_EQ(s.segments()[0].duration, 1.5);
  EXPECT_EQ(s.segments()[0].tau, Eigen::Vector3d(20.0, -3.0, 4.0));
  EXPECT_EQ(s.segments()[0].line, 4);
  EXPECT_EQ(s.segments()[1].line, 6);
  EXPECT_DOUBLE_EQ(s.totalDuration(), 1.75);
  EXPECT_EQ(ControlSchedule::header(3), "duration,tau_theta,tau_1,tau_2,tau_3");
}

TEST(ControlsFile, ErrorsNameFileLineAndColumn) {
  const std::string h = "duration,tau_theta,tau_1\n";
  EXPECT_EQ(messageOf(h + "1,2,x\n", 1), "c.csv:2: column 'tau_1': 'x' is not a number");
  EXPECT_EQ(messageOf(h + "1,2\n", 1),
            "c.csv:2: expected 3 values (duration,tau_theta,tau_1), got 2");
  EXPECT_EQ(messageOf(h + "\n1,2,3,\n", 1),
            "c.csv:3: expected 3 values (duration,tau_theta,tau_1), got 4");
  EXPECT_NE(messageOf(h + "0,2,3\n", 1).find("c.csv:2: column 'duration'"), std::string::npos);
  EXPECT_NE(messageOf(h + "nan,2,3\n", 1).find("c.csv:2: column 'duration'"), std::string::npos);
  EXPECT_NE(messageOf("duration,tau_theta,tau_2\n", 1).find("c.csv:1: header must be"),
            std::string::npos);
  EXPECT_NE(messageOf(h, 1).find("no segments"), std::string::npos);
  EXPECT_NE(messageOf("# nothing\n", 1).find("empty controls file"), std::string::npos);
  EXPECT_THROW(ControlSchedule::load("/nonexistent/ctl.csv", 1), InputError);
}

TEST(TrajectoryWriter, FormatByExtensionAndAtomicWrite) {
  EXPECT_THROW(TrajectoryWriter("out.txt", 2), InputError);
  EXPECT_THROW(TrajectoryWriter("csv", 2), InputError);
  EXPECT_EQ(TrajectoryWriter("a.CSV", 2).format(), TrajectoryWriter::Format::kCsv);
  EXPECT_EQ(TrajectoryWriter("a.json", 2).format(), TrajectoryWriter::Format::kJson);
  EXPECT_EQ(trajectoryCsvHeader(1),
            "t,x,y,phi,theta,l1,dx,dy,dphi,dtheta,dl1,tau_theta,tau_1,fn_1,phase");

  TrajectorySample s;
  s.t = 0.1;
  s.q = VecQ::LinSpaced(5, 1.0, 5.0);
  s.v = VecQ::Constant(5, 1.0 / 3.0);
  s.tau = VecU::Constant(2, -2.5);
  s.f_n = VecC::Constant(1, 7.0);
  s.phase = Phase::kP;
  const std::string dir = ::testing::TempDir();
  TrajectoryWriter csv(dir + "traj_unit.csv", 1), json(dir + "traj_unit.json", 1);
  csv.add(s);
  json.add(s);
  csv.commit();
  json.commit();
  std::ifstream in(dir + "traj_unit.csv");
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header, trajectoryCsvHeader(1));
  EXPECT_EQ(row.substr(row.rfind(',') + 1), "P");
  EXPECT_NE(row.find("0.33333333333333331"), std::string::npos) << "17 digits: " << row;
  const auto j = nlohmann::json::parse(std::ifstream(dir + "traj_unit.json"));
  EXPECT_EQ(j["samples"][0]["v"][0].get<double>(), 1.0 / 3.0);
  EXPECT_EQ(j["samples"][0]["phase"], "P");
  // At most max_samples samples.
  {
    TrajectoryWriter capped(dir + "traj_cap.csv", 1, "--out", 2);
    capped.add(s);
    capped.add(s);
    EXPECT_THROW(capped.add(s), InputError);
  }
  EXPECT_FALSE(std::ifstream(dir + "traj_cap.csv").good());  // never committed
  // A NaN never reaches a file; the streamed temporary file goes with the writer.
  s.q[0] = NAN;
  {
    TrajectoryWriter bad(dir + "traj_nan.csv", 1);
    EXPECT_THROW(bad.add(s), std::runtime_error);
    EXPECT_TRUE(std::ifstream(temporaryPathFor(dir + "traj_nan.csv")).good());
  }
  EXPECT_FALSE(std::ifstream(dir + "traj_nan.csv").good());
  EXPECT_FALSE(std::ifstream(temporaryPathFor(dir + "traj_nan.csv")).good());
}

}  // namespace
}  // namespace rbsf::tools

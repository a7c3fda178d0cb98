// Sprocket drive: tracks its command, respects its torque limit.
#include "trackbed/robot/sprocket_motor.h"

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"

namespace trackbed::robot {
namespace {

TEST(SprocketMotorTest, ReachesTheCommandedSpeedUnderConstantLoad) {
  SprocketMotor m(SprocketMotorOptions{});
  m.Command(4.0);
  for (int k = 0; k < 2000; ++k) m.Step(0.001, 3.0);  // 2 s with 3 N·m of load
  EXPECT_NEAR(m.speed_radps(), 4.0, 1e-3);            // integral action: no droop
}

TEST(SprocketMotorTest, TorqueNeverExceedsTheLimit) {
  SprocketMotorOptions o;
  o.max_torque_nm = 5.0;
  SprocketMotor m(o);
  m.Command(10.0);
  for (int k = 0; k < 3000; ++k) {
    m.Step(0.001, 8.0);  // more load than the motor can give: it stalls backwards
    EXPECT_LE(std::abs(m.torque_nm()), 5.0 + 1e-12);
  }
  EXPECT_LT(m.speed_radps(), 0.0);
}

TEST(SprocketMotorTest, CommandIsClampedToTheSpeedLimit) {
  SprocketMotorOptions o;
  o.max_speed_radps = 3.0;
  SprocketMotor m(o);
  m.Command(-50.0);
  EXPECT_EQ(m.command_radps(), -3.0);
}

TEST(SprocketMotorTest, InvalidOptionsNameTheField) {
  SprocketMotorOptions o;
  o.inertia_kgm2 = 0.0;
  try {
    SprocketMotor m(o);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_STREQ(e.what(), "inertia_kgm2: must be > 0 (got 0)");
  }
}

}  // namespace
}  // namespace trackbed::robot

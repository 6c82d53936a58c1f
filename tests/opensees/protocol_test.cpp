// The sizes OpenSees' elements exchange, against GenericClient.cpp's own rule
// (dataSize = max(given, 1 + 3n + 1, n^2)) and Adapter.cpp's check (each non-zero size
// equals the element's DOFs).
#include "rpsd/opensees/protocol.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rpsd::opensees {
namespace {

TEST(Protocol, AGenericClientAnnouncesItsDofsTheTimeAndTheLargerOf256ThreeNPlusTwoAndNSquared) {
  EXPECT_EQ(generic_client_sizes(1).to_wire(), (std::array<std::int32_t, 11>{1, 1, 1, 0, 1, 0, 0, 0, 1, 0, 256}));
  EXPECT_EQ(generic_client_sizes(20).data_size, 400);    // n^2 = 400 > 256 > 62
  EXPECT_EQ(generic_client_sizes(2, 10).data_size, 10);  // the given 10 > 3n + 2 = 8 > 4
  EXPECT_EQ(generic_client_sizes(3, 1).data_size, 11);   // 3n + 2 = 11 > 9 > 1
}

TEST(Protocol, SizesGoOnTheWireInOpenSeesOrder) {
  const DataSizes s = DataSizes::from_wire({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});
  EXPECT_EQ(s.ctrl_disp, 1);
  EXPECT_EQ(s.ctrl_time, 5);
  EXPECT_EQ(s.daq_disp, 6);
  EXPECT_EQ(s.daq_force, 9);
  EXPECT_EQ(s.data_size, 11);
  EXPECT_THAT(s.text(), testing::HasSubstr("ctrlDisp=1 ctrlVel=2"));
}

TEST(Protocol, ASiteAcceptsAClientOfItsOwnDofsOnly) {
  EXPECT_EQ(check_client_sizes(generic_client_sizes(2), 2), "");
  EXPECT_THAT(check_client_sizes(generic_client_sizes(2), 1), testing::HasSubstr("the element has 2 basic DOFs"));
  DataSizes no_forces = generic_client_sizes(1);
  no_forces.daq_force = 0;
  EXPECT_THAT(check_client_sizes(no_forces, 1), testing::HasSubstr("no forces asked back"));
  DataSizes small = generic_client_sizes(3);
  small.data_size = 5;  // a request needs 1 + 3 + 3 + 3 + 1 = 11
  EXPECT_THAT(check_client_sizes(small, 3), testing::HasSubstr("a message size of 5 doubles, where 11"));
  DataSizes huge = generic_client_sizes(1);
  huge.data_size = kMaxDataSize + 1;
  EXPECT_NE(check_client_sizes(huge, 1), "");
}

TEST(Protocol, AnAdapterIsToldDisplacementsOutAndDisplacementsAndForcesBack) {
  EXPECT_EQ(adapter_sizes(3).to_wire(), (std::array<std::int32_t, 11>{3, 0, 0, 0, 0, 3, 0, 0, 3, 0, 6}));
  EXPECT_EQ(adapter_sizes(1).data_size, 2);  // [action, d] out; [d, f] back
}

}  // namespace
}  // namespace rpsd::opensees

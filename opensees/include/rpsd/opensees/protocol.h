// OpenSees' remote-element protocol as its stock elements speak it (docs/opensees.md):
// no framing, a vector is size x 8 bytes of native doubles, an ID size x 4 bytes of int32,
// every message exactly the agreed length. The setup is 11 int32 sizes; then every message,
// both ways, is data_size doubles, the first of a request being its action.
// Read from OpenSees SRC/element/generic/GenericClient.cpp (the client) and
// SRC/element/adapter/Adapter.cpp (the server), commit 2890cb3.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace rpsd::opensees {

// A request's first double.
enum Action : int {
  kSetTrialResponse = 3,  // [3, disp, vel, accel, time]: no reply
  kCommitState = 5,       // the step converged: no reply
  kGetDaqResponse = 6,    // reply [measured disp, force]
  kGetDisp = 7,
  kGetVel = 8,
  kGetAccel = 9,
  kGetForce = 10,  // reply the forces from index 0
  kGetTime = 11,
  kGetInitialStiff = 12,  // reply an n x n matrix, column-major
  kGetTangentStiff = 13,
  kGetDamp = 14,
  kGetMass = 15,
  kDie = 99,  // the client is done: no reply
};

// The 11 sizes of the setup, in wire order.
struct DataSizes {
  std::int32_t ctrl_disp = 0, ctrl_vel = 0, ctrl_accel = 0, ctrl_force = 0, ctrl_time = 0;
  std::int32_t daq_disp = 0, daq_vel = 0, daq_accel = 0, daq_force = 0, daq_time = 0;
  std::int32_t data_size = 0;  // doubles in every message after the setup

  std::array<std::int32_t, 11> to_wire() const;
  static DataSizes from_wire(const std::array<std::int32_t, 11>& wire);
  std::string text() const;  // "ctrlDisp=1 ctrlVel=1 ... dataSize=256"
  bool operator==(const DataSizes&) const = default;
};

// The longest message rpsd accepts, in doubles (512 KiB): far above any element's
// (n^2 for n basic DOFs), small enough that a garbled size cannot exhaust memory.
inline constexpr std::int32_t kMaxDataSize = 65536;

// What a genericClient with `basic_dofs` DOFs and `-dataSize given` (default 256) announces:
// trial displacement, velocity and acceleration and the time; forces back.
DataSizes generic_client_sizes(int basic_dofs, int given_data_size = 256);
// Checks sizes a client announced against a site with `basic_dofs` DOFs: "" when they fit,
// otherwise a sentence for the user (the two sides disagree on the element's DOFs, ...).
std::string check_client_sizes(const DataSizes& sizes, int basic_dofs);

// What rpsd announces to an adapter of `dofs` DOFs: displacements out, measured
// displacements and forces back.
DataSizes adapter_sizes(int dofs);

}  // namespace rpsd::opensees

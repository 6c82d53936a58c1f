#include "rpsd/opensees/protocol.h"

#include <algorithm>

namespace rpsd::opensees {

std::array<std::int32_t, 11> DataSizes::to_wire() const {
  return {ctrl_disp, ctrl_vel,  ctrl_accel, ctrl_force, ctrl_time, daq_disp,
          daq_vel,   daq_accel, daq_force,  daq_time,   data_size};
}

DataSizes DataSizes::from_wire(const std::array<std::int32_t, 11>& w) {
  return {w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], w[8], w[9], w[10]};
}

std::string DataSizes::text() const {
  const char* names[] = {"ctrlDisp", "ctrlVel",  "ctrlAccel", "ctrlForce", "ctrlTime", "daqDisp",
                         "daqVel",   "daqAccel", "daqForce",  "daqTime",   "dataSize"};
  const auto wire = to_wire();
  std::string text;
  for (std::size_t i = 0; i < wire.size(); ++i) {
    if (i > 0) text += ' ';
    text += names[i];
    text += '=';
    text += std::to_string(wire[i]);
  }
  return text;
}

DataSizes generic_client_sizes(int basic_dofs, int given_data_size) {
  DataSizes s;
  s.ctrl_disp = s.ctrl_vel = s.ctrl_accel = basic_dofs;
  s.ctrl_time = 1;
  s.daq_force = basic_dofs;
  s.data_size = std::max({given_data_size, 1 + 3 * basic_dofs + 1, basic_dofs * basic_dofs});
  return s;
}

std::string check_client_sizes(const DataSizes& s, int basic_dofs) {
  const std::string n = std::to_string(basic_dofs);
  const auto wire = s.to_wire();
  for (std::size_t i = 0; i < 10; ++i) {
    if (wire[i] < 0 || wire[i] > kMaxDataSize) return "a size out of range (" + s.text() + ")";
  }
  if (s.ctrl_disp != basic_dofs) {
    return "the element has " + std::to_string(s.ctrl_disp) + " basic DOFs (ctrlDisp), the site " + n +
           ": give the element as many -dof entries as the site has `element_dofs`";
  }
  for (const std::int32_t size : {s.ctrl_vel, s.ctrl_accel, s.ctrl_force}) {
    if (size != 0 && size != basic_dofs) return "sizes that do not match " + n + " DOFs (" + s.text() + ")";
  }
  if (s.ctrl_time != 0 && s.ctrl_time != 1) return "a time of " + std::to_string(s.ctrl_time) + " values";
  if (s.daq_force != basic_dofs) return "no forces asked back (daqForce=" + std::to_string(s.daq_force) + ")";
  const std::int32_t request = 1 + s.ctrl_disp + s.ctrl_vel + s.ctrl_accel + s.ctrl_force + s.ctrl_time;
  const std::int32_t needed = std::max(request, basic_dofs * basic_dofs);
  if (s.data_size < needed || s.data_size > kMaxDataSize) {
    return "a message size of " + std::to_string(s.data_size) + " doubles, where " + std::to_string(needed) + " to " +
           std::to_string(kMaxDataSize) + " are needed";
  }
  return "";
}

DataSizes adapter_sizes(int dofs) {
  DataSizes s;
  s.ctrl_disp = dofs;
  s.daq_disp = dofs;
  s.daq_force = dofs;
  s.data_size = std::max(1 + dofs, 2 * dofs);
  return s;
}

}  // namespace rpsd::opensees

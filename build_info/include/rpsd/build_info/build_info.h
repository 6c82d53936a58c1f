// What this rpsd was built from: for `rpsd --version` and every summary.json, so that a
// result names the code that produced it.
#pragma once

namespace rpsd::build_info {

// The project's version (CMakeLists.txt), "0.1.0".
const char* version();
// The source tree's commit, "git describe --always --dirty" ("0a1b2c3d4e5f-dirty" when it
// held uncommitted changes), or "unknown" when built outside a git checkout.
const char* commit();

}  // namespace rpsd::build_info

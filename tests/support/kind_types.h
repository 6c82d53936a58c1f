// A config::KindList as googletest types, each named by its kName: a typed suite over a
// list runs every kind registered in it, so that a new kind is covered without a new test
// line.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "rpsd/config/kind_list.h"

namespace rpsd::testing {

template <class List>
struct KindTypes;
template <class... Kinds>
struct KindTypes<config::KindList<Kinds...>> {
  using type = ::testing::Types<Kinds...>;
};

class KindNames {
 public:
  template <class Kind>
  static std::string GetName(int) {
    return std::string(Kind::kName);
  }
};

}  // namespace rpsd::testing

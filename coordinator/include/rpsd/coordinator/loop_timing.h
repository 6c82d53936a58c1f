// When in a step the loop reads its target and feeds the measured force back
// (docs/benchmark.md, "Loop timing"). One policy for every site kind: the coordinator alone
// picks what it sends and what it feeds, so a node, a DDS link or an OpenSees adapter sees
// the same exchange under either timing.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace rpsd::coordinator {

enum class LoopTiming {
  // rpsd's default: the step's command is the target for the end of the period,
  // y_n(t_{k+1}), and the force measured in that exchange is fed back at once.
  kEndOfStep,
  // The RTHS benchmark's Simulink loop: the command is the target at the current sample,
  // y_n(t_k), and the measured force reaches the numerical part through a unit delay, held
  // over the step (the force of the previous exchange). One exchange per step only.
  kTargetNowForceDelayed,
};

inline constexpr std::array<std::string_view, 2> kLoopTimingNames = {"end_of_step", "target_now_force_delayed"};

constexpr std::string_view loop_timing_name(LoopTiming t) { return kLoopTimingNames[static_cast<std::size_t>(t)]; }

constexpr std::optional<LoopTiming> loop_timing_named(std::string_view name) {
  for (std::size_t i = 0; i < kLoopTimingNames.size(); ++i)
    if (kLoopTimingNames[i] == name) return static_cast<LoopTiming>(i);
  return std::nullopt;
}

}  // namespace rpsd::coordinator

// PNG plots through gnuplot's pngcairo terminal. The script is kept beside the PNG so a
// user can edit and redraw it (`gnuplot fig.gp`). Not real-time safe.
#pragma once

#include <filesystem>
#include <string>

namespace rpsd::output {

// Writes `<png without extension>.gp` (terminal and output lines prepended to `script`)
// and runs gnuplot on it from the PNG's folder. Throws std::runtime_error if gnuplot is
// missing or fails.
void render_png(const std::filesystem::path& png, const std::string& script, int width_px = 1000, int height_px = 700);

// Runs gnuplot on a script render_png wrote (or a user edited), from its folder.
void rerender(const std::filesystem::path& gp);

}  // namespace rpsd::output

#include "rpsd/output/gnuplot.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rpsd/output/results_files.h"

namespace rpsd::output {

void render_png(const std::filesystem::path& png, const std::string& script, int width_px, int height_px) {
  std::filesystem::path gp = png;
  gp.replace_extension(".gp");
  write_file_whole(gp, "set terminal pngcairo size " + std::to_string(width_px) + ',' + std::to_string(height_px) +
                           " font 'sans,10'\nset output '" + png.filename().string() + "'\n" + script);
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    throw std::runtime_error("gnuplot not found: run scripts/install-deps.sh (package gnuplot-nox) to draw " +
                             png.string() + "; the data and " + gp.string() + " are written");
  }
  rerender(gp);
}

void rerender(const std::filesystem::path& gp) {
  const std::filesystem::path folder = gp.parent_path().empty() ? std::filesystem::path(".") : gp.parent_path();
  const std::string command = "cd '" + folder.string() + "' && gnuplot '" + gp.filename().string() + "'";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("gnuplot failed on " + gp.string());
}

}  // namespace rpsd::output

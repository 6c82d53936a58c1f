// The kinds of numerical substructure a scenario's `structure:` may be, registered in one
// place (the list below): each names itself (`structure.kind`), reads its keys and makes the
// model configuration it describes, checked by configuring a model from it.
#pragma once

#include <string>
#include <string_view>
#include <variant>

#include "rpsd/config/kind_list.h"
#include "rpsd/config/source.h"
#include "rpsd/substructure/external_structure.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/substructure/matrix_market.h"
#include "rpsd/substructure/shear_building.h"

namespace rpsd::substructure {

// What a structure kind makes: a linear model, a shear building, or the matrices of a
// structure whose restoring force a host program gives.
using StructureConfig = std::variant<LinearMdofParameters, ShearBuildingParameters, ExternalStructureParameters>;
using StructureModel [[deprecated("renamed StructureConfig (docs/migration.md)")]] = StructureConfig;

struct LinearStructure {
  static constexpr std::string_view kName = "linear";
  static constexpr std::string_view kSummary = "M and K in the file: rows, a diagonal or one number, at most 200 DOFs";
  static LinearStructure read(config::Source& structure);
  // Throws std::invalid_argument when no model can be configured from it. Not real-time safe.
  StructureConfig model() const;
  LinearMdofParameters config;
};

struct MatrixMarketStructure {
  static constexpr std::string_view kName = "matrix_market";
  static constexpr std::string_view kSummary =
      "M and K (and C) from Matrix Market files: regular files of at most 256 MB, at most 100000 rows and columns";
  static MatrixMarketStructure read(config::Source& structure);
  // Reads the files (std::runtime_error when one cannot be read) and checks the model.
  StructureConfig model() const;
  MatrixMarketModelFiles files;
  DampingConfig damping = Undamped{};
};

struct ShearBuildingStructure {
  static constexpr std::string_view kName = "shear_building";
  static constexpr std::string_view kSummary = "floor masses and one story spring per floor, bottom up";
  static ShearBuildingStructure read(config::Source& structure);
  StructureConfig model() const;
  ShearBuildingParameters config;
};

// M, C and K0 as the linear kind reads them (composed, not copied) and the name of the host's
// restoring force (external_structure.h). The reader fills in the host's source.
struct ExternalStructure {
  static constexpr std::string_view kName = "external";
  static constexpr std::string_view kSummary =
      "M, K0 (and C) in the file as for linear; R(d) given by a host program by name (a Python callable through "
      "rpsd.run(..., callables=...)); lock-step only";
  static ExternalStructure read(config::Source& structure);
  // Checks the matrices as the linear kind does. Not real-time safe.
  StructureConfig model() const;
  LinearStructure matrices;
  std::string name;
};

using StructureKinds =
    config::KindList<LinearStructure, MatrixMarketStructure, ShearBuildingStructure, ExternalStructure>;

// Whether the host program gives this structure's restoring force (kind external).
inline bool is_external(const StructureConfig& config) noexcept {
  return std::holds_alternative<ExternalStructureParameters>(config);
}

}  // namespace rpsd::substructure

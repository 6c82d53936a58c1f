#include "rpsd/hybrid_test/hybrid_test_config.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "rpsd/substructure/structure_kinds.h"

namespace rpsd::hybrid_test {

Eigen::Index structure_dofs(const TestConfig& config) {
  return std::visit(
      [](const auto& c) -> Eigen::Index {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofParameters>)
          return c.mass_kg.rows();
        else if constexpr (std::is_same_v<C, substructure::ExternalStructureParameters>)
          return c.matrices.mass_kg.rows();
        else
          return static_cast<Eigen::Index>(c.floor_masses_kg.size());
      },
      config.structure);
}

namespace {

// The structure's matrices and law, an external structure's as the linear model of its
// matrices: nothing asked of a host program.
std::unique_ptr<substructure::NumericalModel> configured(const substructure::StructureConfig& structure) {
  return std::visit(
      [](const auto& c) -> std::unique_ptr<substructure::NumericalModel> {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofParameters>) {
          auto model = std::make_unique<substructure::LinearMdofModel>();
          model->configure(c);
          return model;
        } else if constexpr (std::is_same_v<C, substructure::ExternalStructureParameters>) {
          auto model = std::make_unique<substructure::LinearMdofModel>();
          model->configure(c.matrices);
          return model;
        } else {
          auto model = std::make_unique<substructure::ShearBuilding>();
          model->configure(c);
          return model;
        }
      },
      structure);
}

using Structure = substructure::StructureConfig;

// The structure less the stiffness of the specimens it includes (model units), K_N = K - K_E,
// refused unless K_N stays positive definite: a numerical part that could not stand alone.
Structure without_included_stiffness(const TestConfig& config) {
  auto structure = config.structure;
  if (std::none_of(config.experimental.begin(), config.experimental.end(),
                   [](const auto& e) { return e.stiffness_in_structure; }))
    return structure;
  auto* linear = std::get_if<substructure::LinearMdofParameters>(&structure);
  if (linear == nullptr) {
    throw std::invalid_argument(
        "experimental[].specimen: the structure must be the whole reference structure's matrices (kind linear)");
  }
  Eigen::MatrixXd k = linear->stiffness_n_per_m.to_dense();
  for (const auto& e : config.experimental) {
    if (!e.stiffness_in_structure || e.dof.dof >= k.rows()) continue;
    k(e.dof.dof, e.dof.dof) -= e.dof.force_scale * e.dof.displacement_scale * e.dof.specimen_stiffness_estimate_n_per_m;
  }
  const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(k, Eigen::EigenvaluesOnly).eigenvalues()(0);
  if (!(lowest > 0.0)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", lowest);
    throw std::invalid_argument(
        "the numerical part's stiffness K_N = K - K_E (the structure's less the "
        "specimens') is not positive definite (smallest eigenvalue " +
        std::string(text) + " N/m): a specimen takes more stiffness than the structure has there");
  }
  linear->stiffness_n_per_m = linalg::StructuralMatrix(k).converted(linear->stiffness_n_per_m.storage());
  return structure;
}

// The structure less the specimens' own mass (model units: force scale x displacement scale).
Structure without_specimen_mass(const TestConfig& config, Structure structure) {
  for (const auto& e : config.experimental) {
    if (e.specimen_mass_kg == 0.0) continue;
    const double m = e.dof.force_scale * e.dof.displacement_scale * e.specimen_mass_kg;
    const auto d = e.dof.dof;
    double left = 0.0;
    std::visit(
        [&](auto& c) {
          using C = std::decay_t<decltype(c)>;
          const auto less_specimen = [&](substructure::LinearMdofParameters& linear) {
            Eigen::MatrixXd dense = linear.mass_kg.to_dense();
            if (d < dense.rows()) left = dense(d, d) -= m;
            linear.mass_kg = linalg::StructuralMatrix(dense);
          };
          if constexpr (std::is_same_v<C, substructure::LinearMdofParameters>) {
            less_specimen(c);
          } else if constexpr (std::is_same_v<C, substructure::ExternalStructureParameters>) {
            less_specimen(c.matrices);
          } else {
            if (d < static_cast<Eigen::Index>(c.floor_masses_kg.size())) left = c.floor_masses_kg[d] -= m;
          }
        },
        structure);
    if (!(left > 0.0)) {
      throw std::invalid_argument("experimental[].specimen_mass_kg: the specimen on DOF " + std::to_string(d) +
                                  " is heavier than the structure's mass there");
    }
  }
  return structure;
}

}  // namespace

linalg::StructuralMatrix whole_structure_mass(const TestConfig& config) { return configured(config.structure)->mass(); }

namespace {

// The numerical part's structure: the file's less what the specimens take.
Structure numerical_part(const TestConfig& config, SpecimenShare share) {
  const bool left_to_specimens = share == SpecimenShare::kLeftToSpecimens;
  const bool specimens_own = std::any_of(config.experimental.begin(), config.experimental.end(), [](const auto& e) {
    return e.specimen_damping_n_s_per_m > 0.0 || e.specimen_mass_kg > 0.0;
  });
  const Structure numerical = without_included_stiffness(config);
  if (!config.whole_structure_damping && !specimens_own) return numerical;
  auto structure = left_to_specimens ? without_specimen_mass(config, numerical) : numerical;
  Eigen::MatrixXd c;
  if (config.whole_structure_damping) {
    // The whole structure's C, from M and K0 with the specimens' stiffness; the numerical
    // part keeps it less the specimens' own damping (in model units, as their stiffness).
    const auto undamped = configured(numerical);
    substructure::Partition partition;
    partition.configure(partition_config(config, undamped->dofs()));
    const linalg::StructuralMatrix k_whole = partition.with_specimen_stiffness(undamped->initial_stiffness());
    c = substructure::build_damping(*config.whole_structure_damping, undamped->mass(), k_whole,
                                    "whole_structure_damping: ")
            .c.to_dense();
  } else {
    // The structure's own damping is the numerical part's; the whole has the specimens' too.
    c = configured(without_specimen_mass(config, numerical))->damping().to_dense();
  }
  const double sign =
      config.whole_structure_damping ? (left_to_specimens ? -1.0 : 0.0) : (left_to_specimens ? 0.0 : 1.0);
  for (const auto& e : config.experimental) {
    c(e.dof.dof, e.dof.dof) += sign * e.dof.force_scale * e.dof.displacement_scale * e.specimen_damping_n_s_per_m;
  }
  std::visit(
      [&c](auto& s) {
        const substructure::DampingMatrix matrix{linalg::StructuralMatrix(c)};
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, substructure::ExternalStructureParameters>) {
          s.matrices.damping = matrix;
        } else {
          s.damping = matrix;
        }
      },
      structure);
  return structure;
}

}  // namespace

std::unique_ptr<substructure::NumericalModel> make_numerical_model(const TestConfig& config, SpecimenShare share) {
  const Structure structure = numerical_part(config, share);
  if (const auto* external = std::get_if<substructure::ExternalStructureParameters>(&structure)) {
    auto model = std::make_unique<substructure::ExternalStructureModel>();
    model->configure(*external);
    return model;
  }
  return configured(structure);
}

std::unique_ptr<substructure::NumericalModel> numerical_matrices(const TestConfig& config, SpecimenShare share) {
  return configured(numerical_part(config, share));
}

bool uses_external_parts(const TestConfig& config) {
  return compensation::is_external(config.compensation) || substructure::is_external(config.structure);
}

substructure::PartitionConfig partition_config(const TestConfig& s, Eigen::Index dofs) {
  substructure::PartitionConfig split;
  split.dofs = dofs;
  for (const auto& e : s.experimental) split.experimental.push_back(e.dof);
  split.influence = s.influence;
  for (const auto& site : s.opensees_sites) {
    if (site.stiffness_n_per_m.size() == 0) continue;
    // The site's channels, in its DOF order.
    std::vector<Eigen::Index> channels;
    for (const auto& e : s.experimental) {
      if (e.site_id == site.adapter.site_id) channels.push_back(e.dof.actuator_channel);
    }
    std::sort(channels.begin(), channels.end());
    for (Eigen::Index i = 0; i < site.stiffness_n_per_m.rows(); ++i) {
      for (Eigen::Index j = i + 1; j < site.stiffness_n_per_m.cols(); ++j) {
        if (site.stiffness_n_per_m(i, j) != 0.0) {
          split.couplings.push_back({channels[static_cast<std::size_t>(i)], channels[static_cast<std::size_t>(j)],
                                     site.stiffness_n_per_m(i, j)});
        }
      }
    }
  }
  // A setup's specimen couples its DOFs: its off-diagonal stiffness, in model units
  // (force_scale of the row's DOF times displacement_scale of the column's).
  for (const auto& setup : s.setups) {
    const auto n = static_cast<Eigen::Index>(setup.channels.size());
    if (setup.specimen_stiffness.rows() != n) continue;
    for (Eigen::Index i = 0; i < n; ++i) {
      for (Eigen::Index j = i + 1; j < n; ++j) {
        if (setup.specimen_stiffness(i, j) == 0.0) continue;
        const auto on_channel = [&split](int channel) -> const substructure::ExperimentalDof& {
          return *std::find_if(split.experimental.begin(), split.experimental.end(),
                               [channel](const auto& e) { return e.actuator_channel == channel; });
        };
        const auto& a = on_channel(setup.channels[static_cast<std::size_t>(i)]);
        const auto& b = on_channel(setup.channels[static_cast<std::size_t>(j)]);
        split.couplings.push_back({a.actuator_channel, b.actuator_channel,
                                   a.force_scale * b.displacement_scale * setup.specimen_stiffness(i, j)});
      }
    }
  }
  return split;
}

}  // namespace rpsd::hybrid_test

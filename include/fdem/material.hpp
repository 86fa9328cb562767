// Material constants (docs/theory.md §2): on their own so the material law
// (src/fdem/material/) needs this struct only, not the whole Model.
#pragma once

#include <string>

#include "fdem/fracture.hpp"
#include "fdem/math.hpp"

namespace fdem {

enum class PlaneMode { Strain, Stress };

/// Isotropic hyperelastic material (docs/theory.md §2, spec §3.1). SI units.
struct Material {
    std::string name;
    Real density = 0;         ///< rho [kg/m^3], > 0
    Real youngs_modulus = 0;  ///< E [Pa], > 0
    Real poisson_ratio = 0;   ///< nu [-], in [0, 0.5)
    PlaneMode plane = PlaneMode::Strain;
    Real viscosity = 0;      ///< eta [Pa s] of the viscous stress eta*D (theory §2.3), >= 0
    Real damping_ratio = 0;  ///< xi [-]: adds eta = 2 h xi sqrt(E rho) per element (theory §2.3)
    /// [material.fracture] (spec fracture.md §10): the joint parameters of bodies of this
    /// material that have fracture; has_fracture = false without that table
    bool has_fracture = false;
    JointMaterial fracture;
    // derived at build time (theory eq. 2.5): effective 2-D Lame constants
    Real lambda = 0;  ///< [Pa]; for plane stress the reduced 2 lambda mu / (lambda + 2 mu)
    Real mu = 0;      ///< shear modulus [Pa]
};

}  // namespace fdem

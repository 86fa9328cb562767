// Umbrella header of the fdem library.
#pragma once

#include "fdem/build.hpp"
#include "fdem/checks.hpp"
#include "fdem/error.hpp"
#include "fdem/fracture.hpp"
#include "fdem/material.hpp"
#include "fdem/math.hpp"
#include "fdem/measure.hpp"
#include "fdem/mesh.hpp"
#include "fdem/model.hpp"
#include "fdem/output.hpp"
#include "fdem/scenario.hpp"
#include "fdem/simulate.hpp"
#include "fdem/simulation.hpp"
#include "fdem/state.hpp"
#include "fdem/version.hpp"

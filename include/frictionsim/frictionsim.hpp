// Umbrella header: friction laws, rigs, contact models, analysis and the header-only solver.
// SUNDIALS is not included here: add <frictionsim/simulate.hpp> (CVODE + method dispatch) for that.
#pragma once

#include "analysis/cycle_mean.hpp"
#include "analysis/limit_cycle.hpp"
#include "contact/hydraulic_oscillator.hpp"
#include "error.hpp"
#include "friction/coulomb.hpp"
#include "friction/dahl.hpp"
#include "friction/hysteretic.hpp"
#include "friction/lugre.hpp"
#include "friction/power_law.hpp"
#include "friction/stribeck.hpp"
#include "rigs/axial_rig.hpp"
#include "rigs/kinematic_rig.hpp"
#include "rigs/reference_setups.hpp"
#include "rigs/signals.hpp"
#include "rigs/torsional_rig.hpp"
#include "solve/dormand_prince.hpp"
#include "solve/hybrid_loop.hpp"
#include "solve/options.hpp"
#include "solve/result.hpp"
#include "solve/simulate.hpp"

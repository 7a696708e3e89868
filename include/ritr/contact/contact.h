#pragma once
// Umbrella header of the contact module (IPC barrier, lagged friction, broad phase, CCD).
#include <ritr/contact/barrier.h>
#include <ritr/contact/broad_phase.h>
#include <ritr/contact/ccd.h>
#include <ritr/contact/collision_surface.h>
#include <ritr/contact/constraints.h>
#include <ritr/contact/distance.h>
#include <ritr/contact/friction.h>

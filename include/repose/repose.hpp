// Umbrella header: everything a program embedding repose needs.
#pragma once

#include "repose/error.hpp"
#include "repose/geometry/hull.hpp"
#include "repose/geometry/mass.hpp"
#include "repose/geometry/mesh.hpp"
#include "repose/geometry/shapes.hpp"
#include "repose/geometry/types.hpp"
#include "repose/io/mesh_io.hpp"
#include "repose/model/orientation.hpp"
#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/output/files.hpp"
#include "repose/output/report.hpp"
#include "repose/sim/settle.hpp"

// The numbers of a URDF, read strictly before urdfdom reads them (issue 39): urdfdom takes
// "1,5e-3" (a decimal comma) as 1 or 0, "abc" as 0 and "nan" as NaN, without a word, and a
// robot then runs with a wrong mass or inertia. Every numeric attribute of the elements URDF
// defines (origin, axis, mass, inertia, limit, dynamics, geometry, colour, ...) must be a
// list of the expected count of finite decimal numbers, each token read whole (locale-free);
// masses and inertias must also be at most kMaxUrdfMass (larger ones overflow the dynamics:
// 1e308 kg was reported as "massless links?").
#pragma once

#include <tinyxml.h>

#include <string>

namespace stiction::scene {

inline constexpr double kMaxUrdfMass = 1e12;  // kg, and kg m^2 for inertias

// Throws UrdfError "ORIGIN:LINE:COL: <element> attribute=\"text\": why" at the first bad one.
void check_urdf_numbers(const TiXmlDocument& xml, const std::string& origin);

}  // namespace stiction::scene

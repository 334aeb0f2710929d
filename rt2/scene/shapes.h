// rt2/scene/shapes.h — procedural triangle meshes: box, cylinder, icosphere, cube and a chair.
//
// Each generator returns a self-contained rt2::Mesh whose faces all use `material` and whose
// vertices all carry a unit normal (normals.size() == positions.size()), so meshes can be
// combined with Mesh::append without losing smooth shading. Every face is wound
// counter-clockwise seen from outside: cross(v1 - v0, v2 - v0) points out of the solid.
// Triangle counts are exact functions of the arguments (given with each generator) so a
// scene can be built to a prescribed size, as make_chair is. Invalid arguments throw
// rt2::Error with a one-line message; nothing is clamped silently. Points use w = 0.
#pragma once

#include <cstdint>

#include "rt2/scene/mesh.h"

namespace rt2 {

// The axis-aligned box [lo, hi] (lo < hi in x, y and z), each face split into
// subdivisions x subdivisions (>= 1) quads of two triangles: 12 * subdivisions^2 triangles,
// 6 * (subdivisions + 1)^2 vertices. Vertices are duplicated per face so every normal is the
// exact face normal (flat shading). Open at the edges topologically (use make_cube for a
// watertight box); the vertex coordinates equal lo and hi exactly on the faces.
Mesh make_box(const vec4& lo, const vec4& hi, int subdivisions, std::uint32_t material);

// A cylinder from `base_center` along `axis` (unit length within 1e-4; it is not normalised
// for you) for `height` (> 0), of `radius` (> 0), with `segments` (>= 3) around and `rings`
// (>= 1) along the axis.
// Side: 2 * segments * rings triangles with smooth (radial) normals; with `caps`, two flat
// discs of `segments` triangles each (a fan around the centre; rim vertices duplicated so
// the cap normals are exactly -axis and +axis). Total 2 * segments * (rings + caps).
Mesh make_cylinder(const vec4& base_center, const vec4& axis, float radius, float height,
                   int segments, int rings, bool caps, std::uint32_t material);

// A sphere approximated by a subdivided icosahedron: 20 * 4^subdivisions triangles,
// 10 * 4^subdivisions + 2 vertices, subdivisions in [0, 10]. Closed and watertight: vertices
// are shared, so every edge is used by exactly two faces in opposite directions. Every
// vertex lies at distance `radius` (> 0) from `center`; normals are radial.
Mesh make_icosphere(const vec4& center, float radius, int subdivisions, std::uint32_t material);

// The cube center ± half_size (> 0): 8 shared vertices and 12 triangles, closed and
// watertight. With shared corners there is no exact face normal per vertex, so each vertex
// normal is the normalised corner direction (±1, ±1, ±1) / sqrt(3); interpolated shading
// therefore looks rounded. Use make_box for a flat-shaded box.
Mesh make_cube(const vec4& center, float half_size, std::uint32_t material);

// A dining chair standing on y = 0, centred on x = z = 0, facing +z with its back at -z:
// four legs, a seat (top at y = 0.45, 0.45 x 0.45), two back posts with ball finials, a
// back rail and three slats (top ~0.955), and four stretchers between the legs.
// 10,816 triangles (see shapes.cpp for the arithmetic and why not the thesis's 10,817).
Mesh make_chair(std::uint32_t material);

}  // namespace rt2

// A kinematic tree (BodyVisual::Kind::tree) at time t: its link poses from the joint
// angles of the track, the points that frame it, and its draw items: the URDF's visuals
// (box, cylinder, sphere, and meshes read from their files: each part of a mesh in the
// URDF's colour, else the file's own) on their links, or, for a tree without visuals, a
// stick figure: a rod from each joint to its children's joints (or to twice its centre of
// mass for a leaf) and a dark cylinder along each joint axis.
#pragma once

#include <optional>
#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

// World poses of the tree's link frames at t.
std::vector<components::LinkPose> tree_poses(const BodyVisual& tree, const PoseTrack& poses,
                                             int index, double t);
// The joints, the ends of the links' rods and the corners of the visuals' bounding cubes.
// `links_only`: those of the links alone, without the fixed base and its visuals (what a
// follow camera frames of a fixed-base robot).
std::vector<core::Vec3> tree_points(const BodyVisual& tree, const PoseTrack& poses, int index,
                                    double t, bool links_only = false);
// How far from the axis through `centre` along the unit `axis` (world) the visuals of link
// `link` reach that sit around it (the centre of their bounding box within a quarter of their
// reach from the axis: a turret, a joint's hub; not a beam that leaves the joint sideways),
// by the corners of their bounding boxes; 0 without such visuals. A motor's arc about the
// joint goes outside them (mechanism_items.hpp).
double hub_reach(const BodyVisual& tree, const std::vector<components::LinkPose>& links, int link,
                 const core::Vec3& centre, const core::Vec3& axis);
void add_tree_items(std::vector<DrawItem>& items, const BodyVisual& tree, const PoseTrack& poses,
                    int index, double t);
// Where the floor goes under a scene of fixed-base robots (every body a tree drawn with its
// visuals; no springs or penalty joints): at the lowest point of their bases' visuals (the
// base origin for a base without any), so that each robot stands on it instead of floating above a
// floor put under its reach. Nothing when a moving link goes below that height during the run (an
// arm that hangs or swings beneath its base, or moves in its base's plane): the usual floor under
// everything is drawn then.
std::optional<double> tree_base_floor(const Drawing& scene, const PoseTrack& poses);

}  // namespace stiction::render

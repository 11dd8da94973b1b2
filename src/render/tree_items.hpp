// A kinematic tree (BodyVisual::Kind::tree) at time t: its link poses from the joint
// angles of the track, the points that frame it, and its draw items: the URDF's visual
// primitives (box, cylinder, sphere) on their links, or, for a tree without visuals, a
// stick figure: a rod from each joint to its children's joints (or to twice its centre of
// mass for a leaf) and a dark cylinder along each joint axis.
#pragma once

#include <vector>

#include "render/scene_view.hpp"

namespace stiction::render {

// World poses of the tree's link frames at t.
std::vector<components::LinkPose> tree_poses(const BodyVisual& tree, const PoseTrack& poses,
                                             int index, double t);
// The joints, the ends of the links' rods and the corners of the visuals' bounding cubes.
std::vector<core::Vec3> tree_points(const BodyVisual& tree, const PoseTrack& poses, int index,
                                    double t);
void add_tree_items(std::vector<DrawItem>& items, const BodyVisual& tree, const PoseTrack& poses,
                    int index, double t);

}  // namespace stiction::render

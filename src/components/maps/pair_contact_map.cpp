#include "components/maps/pair_contact_map.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::components {

using core::BodyMotion;
using core::Vec3;

namespace {

PairProbe sphere_sphere(double ra, double rb, const BodyMotion& a, const BodyMotion& b) {
  const Vec3 d = a.p - b.p;
  const double dist = d.norm();
  PairProbe out;
  out.n = dist > 0.0 ? Vec3(d / dist) : Vec3::UnitZ();
  out.depth = ra + rb - dist;
  out.point = b.p + (rb - 0.5 * out.depth) * out.n;
  return out;
}

// A sphere (centre c, radius r) against a box (pose `box`, half sides h): n pushes the sphere.
PairProbe sphere_box(double r, const Vec3& c, const Vec3& h, const BodyMotion& box) {
  const Vec3 local = box.q.conjugate() * (c - box.p);
  const Vec3 clamped = local.cwiseMax(-h).cwiseMin(h);
  PairProbe out;
  Vec3 surface = clamped;  // the box's surface point, box frame
  Vec3 n_local;
  const Vec3 away = local - clamped;
  const double dist = away.norm();
  if (dist > 0.0) {
    n_local = away / dist;
    out.depth = r - dist;
  } else {  // centre inside: out through the face it is least deep under
    int k = 0;
    const Vec3 under = h - local.cwiseAbs();
    under.minCoeff(&k);
    const double side = local[k] >= 0.0 ? 1.0 : -1.0;
    n_local = side * Vec3::Unit(k);
    surface[k] = side * h[k];
    out.depth = r + under[k];
  }
  out.n = box.q * n_local;
  out.point = box.p + box.q * surface - 0.5 * out.depth * out.n;
  return out;
}

// Half the extent of a box (rotation q, half sides h) along the unit direction u.
double support(const core::Quat& q, const Vec3& h, const Vec3& u) {
  const Vec3 local = q.conjugate() * u;
  return h.dot(local.cwiseAbs());
}

// The pair's normal (from b toward a) and whether it is a face of b (else of a).
struct PairAxis {
  Vec3 u;
  bool face_of_b;
};

PairAxis box_axis(const Vec3& ha, const Vec3& hb, const BodyMotion& a, const BodyMotion& b) {
  const Vec3 d = a.p - b.p;
  const double kFaceTie = 1e-9 * std::max(ha.maxCoeff(), hb.maxCoeff());
  PairAxis best{Vec3::UnitZ(), true};
  double least = 0.0;
  bool first = true;
  // b's faces first: a tie (equal boxes stacked exactly) goes to b.
  for (int side = 0; side < 2; ++side) {
    const core::Quat& q = side == 0 ? b.q : a.q;
    for (int k = 0; k < 3; ++k) {
      const Vec3 axis = q * Vec3::Unit(k);
      const double overlap =
          support(a.q, ha, axis) + support(b.q, hb, axis) - std::abs(axis.dot(d));
      // The first box's face must be clearly better: rounding would otherwise flip the
      // choice between two parallel faces (a stack), and the contact with it.
      const bool better = side == 0 ? overlap < least : overlap < least - kFaceTie;
      if (first || better) {
        least = overlap;
        best = {axis.dot(d) >= 0.0 ? axis : Vec3(-axis), side == 0};
        first = false;
      }
    }
  }
  return best;
}

// Corner `corner` of `owner` (half sides ho) against the face of `face` (half sides hf)
// whose outward normal is u; the probe's n is u (it pushes the owner).
PairProbe corner_on_face(const Vec3& ho, int corner, const BodyMotion& owner, const Vec3& hf,
                         const BodyMotion& face, const Vec3& u) {
  const Vec3 c = owner.point(box_corner(ho, corner));
  const Vec3 local = face.q.conjugate() * (c - face.p);
  const Vec3 u_local = face.q.conjugate() * u;
  int k = 0;
  u_local.cwiseAbs().maxCoeff(&k);
  PairProbe out;
  out.n = u;
  // Over the face's outline (a relative tolerance for rounding: a corner of a box stacked
  // exactly on an equal one lies on the outline).
  const double tol = 1e-9 * hf.maxCoeff();
  bool over = true;
  for (int j = 0; j < 3; ++j) {
    if (j != k && std::abs(local[j]) > hf[j] + tol) over = false;
  }
  const double depth = support(face.q, hf, u) - u.dot(c - face.p);
  out.depth = over ? depth : std::min(depth, 0.0) - 1.0;  // off the outline: open
  out.point = c + 0.5 * out.depth * u;
  return out;
}

}  // namespace

Vec3 box_corner(const Vec3& h, int i) {
  return {(i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(), (i & 4 ? 1 : -1) * h.z()};
}

PairProbe probe_pair(const PairShape& s, const BodyMotion& a, const BodyMotion& b) {
  switch (s.kind) {
    case PairKind::sphere_sphere:
      return sphere_sphere(s.radius_a, s.radius_b, a, b);
    case PairKind::sphere_box:
      return sphere_box(s.radius_a, a.p, s.half_b, b);
    case PairKind::box_sphere: {
      PairProbe out = sphere_box(s.radius_b, b.p, s.half_a, a);
      out.n = -out.n;
      return out;
    }
    case PairKind::box_box: {
      const PairAxis axis = box_axis(s.half_a, s.half_b, a, b);
      const bool of_a = s.corner < 8;
      if (of_a != axis.face_of_b) {  // this box's face is the reference: its corners are open
        PairProbe out;
        out.n = axis.u;
        out.depth = -1.0;
        out.point = of_a ? a.point(box_corner(s.half_a, s.corner))
                         : b.point(box_corner(s.half_b, s.corner - 8));
        return out;
      }
      if (of_a) return corner_on_face(s.half_a, s.corner, a, s.half_b, b, axis.u);
      PairProbe out = corner_on_face(s.half_b, s.corner - 8, b, s.half_a, a, -axis.u);
      out.n = -out.n;
      return out;
    }
  }
  return {};
}

void PairContactMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const BodyMotion a = motion_a(x), b = motion_b(x);
  const PairProbe pr = probe_pair(shape_, a, b);
  x_hat[0] = pr.depth;
  x_hat.segment<3>(1) = pr.n;
  x_hat.segment<3>(4) = a.point_velocity(pr.point) - b.point_velocity(pr.point);
}

void PairContactMap::apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const {
  const BodyMotion a = motion_a(x), b = motion_b(x);
  const PairProbe pr = probe_pair(shape_, a, b);
  const Vec3 on_a = -u.head<3>();
  a_.add_wrench(a, pr.point - a.p, on_a, Vec3::Zero(),
                u_hat.segment(slot_a_.input_offset, slot_a_.input_size));
  b_.add_wrench(b, pr.point - b.p, -on_a, Vec3::Zero(),
                u_hat.segment(slot_b_.input_offset, slot_b_.input_size));
}

}  // namespace stiction::components

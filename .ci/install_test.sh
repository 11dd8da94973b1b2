#!/usr/bin/env bash
# Installs build/ into a temporary prefix, moves the prefix elsewhere and the build tree out
# of the way, then: the installed binary must find its bundled scenes and font relative to
# itself (a scene placed only in the moved prefix is listed), run a scene with plots and
# one with a video (the render plugin is found relative to the binary too), and
# the example in examples/viscous_coulomb_joint must configure against the installed
# package (find_package(stiction)), build, and match its closed forms.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
work=$(mktemp -d)
away="$root/build.moved-away.$$"
restore() {
  [ -d "$away" ] && mv "$away" "$root/build"
  rm -rf "$work"
}
trap restore EXIT

cmake --install build --prefix "$work/prefix" >/dev/null
mv "$work/prefix" "$work/moved"
mv "$root/build" "$away"
prefix="$work/moved"

# A scene that exists only in the moved prefix: listed only if the lookup is relative.
sed 's/^name = .*/name = "ci_moved_prefix"/' scenes/sphere_roll.toml > "$prefix/share/stiction/scenes/ci_moved_prefix.toml"
cd "$work"
"$prefix/bin/stiction" scenes | grep -q '^ci_moved_prefix ' || { echo "installed binary does not see its moved prefix" >&2; exit 1; }
"$prefix/bin/stiction" run ci_moved_prefix --no-video --quiet --out "$work/run"
grep -q '"status": "ok"' "$work/run/summary.json"
test -s "$work/run/plots/fig4_sphere.png"  # the font came from the moved prefix too
# The render plugin, loaded from the moved prefix (the build tree is gone).
"$prefix/bin/stiction" run ci_moved_prefix --no-plots --duration 0.1 --quiet --out "$work/video"
test -s "$work/video/video.mp4"

cmake -S "$root/examples/viscous_coulomb_joint" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/example" >/dev/null
"$work/example/viscous_coulomb_joint" "$work/example.csv"
test -s "$work/example.csv"
echo "install test: ok (prefix moved, build tree moved, example built against the package)"

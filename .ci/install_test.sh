#!/usr/bin/env bash
# Installs build/ into a temporary prefix, moves the prefix elsewhere and the build tree out
# of the way, then: the installed binary must find its bundled scenes and font relative to
# itself (a scene placed only in the moved prefix is listed), run a scene with plots and
# one with a video (the render plugin is found relative to the binary too), and
# the example in examples/viscous_coulomb_joint must configure against the installed
# package (find_package(stiction)), build, and match its closed forms.
# The Python package from the moved prefix (Debian's /usr/bin/python3, PYTHONPATH on its
# dist-packages) must import, list the prefix-only scene, run it, render a frame and write a
# plot, with the font from the moved prefix in both the render plugin and the figures; and a
# program linking stiction::services must build against the package and run a scene.
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

# The Python module, from the moved prefix only.
python=/usr/bin/python3
pythonpath=$(echo "$prefix"/lib/python3*/dist-packages)
test -f "$pythonpath/stiction/__init__.py" || { echo "no Python package in $prefix/lib/python3*/dist-packages" >&2; exit 1; }
export STICTION_CACHE_DIR=off  # the step guard's cache: nothing written outside $work
PYTHONPATH="$pythonpath" "$python" - "$prefix" "$work/python" <<'PY'
import os
import sys
from pathlib import Path

prefix, out = Path(sys.argv[1]), Path(sys.argv[2])
import stiction

assert Path(stiction.__file__).resolve().is_relative_to(prefix), stiction.__file__
assert os.environ["STICTION_DATA_DIR"] == str(prefix / "share" / "stiction"), os.environ.get("STICTION_DATA_DIR")
assert "ci_moved_prefix" in stiction.scenes(), "the package does not see its moved prefix"
result = stiction.run(stiction.Scene("ci_moved_prefix").set("render.size", [160, 90]), duration=0.2)
assert result.status == "ok", result.status
frame = stiction.frame(result, 0.1)  # the render plugin from the moved prefix
assert frame.shape == (90, 160, 4) and frame[..., :3].std() > 10, "a blank frame"
plots = result.write_plots(out / "plots")
assert [p.name for p in plots] == ["fig4_sphere.png", "signals_1.png", "signals_2.png"], plots
assert all(p.stat().st_size > 10000 for p in plots)
print(f"python: {len(result)} rows, a {frame.shape[1]}x{frame.shape[0]} frame, {len(plots)} plots from {prefix}")
PY
# The font both sides used is the moved prefix's: with that copy unreadable, the frame (drawn
# by the render plugin, which has its own copy of the libraries) and the plots both fail
# naming it, although the source tree still holds a good one.
font="$prefix/share/stiction/assets/DejaVuSans.ttf"
mv "$font" "$font.good"
echo "not a font" > "$font"
PYTHONPATH="$pythonpath" "$python" - "$font" <<'PY'
import sys
import stiction

font = sys.argv[1]
result = stiction.run(stiction.Scene("ci_moved_prefix").set("render.size", [160, 90]), duration=0.1)
for draw in (lambda: stiction.frame(result, 0.05), lambda: result.write_plots("plots")):
    try:
        draw()
    except stiction.Error as e:
        assert font in str(e), f"the error does not name the moved prefix's font: {e}"
    else:
        raise AssertionError("drew with a font that is not the moved prefix's")
PY
mv "$font.good" "$font"

# A program on the services library (stiction::services), as the Python module uses it.
mkdir -p "$work/services_user"
cat > "$work/services_user/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(services_user LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(stiction 0.1 REQUIRED)
add_executable(services_user main.cpp)
target_link_libraries(services_user PRIVATE stiction::services)
CMAKE
cat > "$work/services_user/main.cpp" <<'CPP'
// Runs a bundled scene through the services and writes its figures: argv[1] is the prefix.
#include <cstdio>

#include "services/plot_outputs.hpp"
#include "services/run_outputs.hpp"
#include "services/run_service.hpp"
#include "sys/data_dirs.hpp"

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  stiction::sys::set_install_root(argv[1]);
  stiction::services::RunRequest request;
  request.overrides.duration = 0.2;
  stiction::services::PreparedRun run = stiction::services::prepare_run(
      stiction::scene::load_scene(stiction::scene::SceneSource{"ci_moved_prefix"}), request);
  const stiction::services::RunOutcome outcome = stiction::services::simulate_run(run, request);
  const auto plots = stiction::services::write_run_plots(
      run.plot_specs, outcome.result,
      stiction::services::plot_rows(outcome.result.trajectory), argv[2], std::nullopt);
  std::printf("services: %d rows, %zu plots\n", outcome.result.trajectory.row_count(), plots.size());
  return plots.empty() ? 1 : 0;
}
CPP
cmake -S "$work/services_user" -B "$work/services_user/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/services_user/build" >"$work/services_user/build.log" || { cat "$work/services_user/build.log" >&2; exit 1; }
"$work/services_user/build/services_user" "$prefix" "$work/services_user/plots"
test -s "$work/services_user/plots/fig4_sphere.png"

cmake -S "$root/examples/viscous_coulomb_joint" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/example" >/dev/null
"$work/example/viscous_coulomb_joint" "$work/example.csv"
test -s "$work/example.csv"
echo "install test: ok (prefix moved, build tree moved; Python package, services user and example built against the package)"

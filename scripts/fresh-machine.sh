#!/usr/bin/env bash
# Times the README's two quick-start commands as a new user meets them: on a fresh Debian 12 root
# (debootstrap --variant=minbase bookworm: nothing installed but Debian's minimal base, no compiler, no git),
# into which this checkout's HEAD is cloned. Needs root, debootstrap (installed if missing) and Debian's archive.
#   scripts/fresh-machine.sh [--ci | --quickstart-only] [--keep] [DIR]
#     DIR     where the root is made (default /var/tmp/repose-fresh); emptied first
#     --ci    also run .ci/run in the same root after the two commands (its time is then the sanitizer
#             build, its tests and the fuzzers on top of scripts/test.sh's build, which it reuses)
#     --quickstart-only   time only the first command
#     --keep  leave the root in place afterwards (default: removed)
# Prints each command's exit code and wall time, and checks that `repose` is on the PATH and `import repose`
# works from outside the checkout. Logs: DIR.log/. The pristine debootstrap root is cached in
# /var/cache/repose-fresh/bookworm-minbase.tar (debootstrap's output, not part of the timed commands).
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
ci=0
keep=0
quickstart_only=0
dir=/var/tmp/repose-fresh
for arg in "$@"; do
  case "$arg" in
    --ci) ci=1 ;;
    --keep) keep=1 ;;
    --quickstart-only) quickstart_only=1 ;;
    -*) echo "fresh-machine.sh: unknown option '$arg' (options: --ci, --quickstart-only, --keep)" >&2; exit 2 ;;
    *) dir="$arg" ;;
  esac
done
[ "$(id -u)" -eq 0 ] || { echo "fresh-machine.sh: needs root (debootstrap, chroot, mount)" >&2; exit 2; }
command -v debootstrap >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null

cache=/var/cache/repose-fresh/bookworm-minbase.tar
if [ ! -f "$cache" ]; then
  mkdir -p "$(dirname "$cache")"
  scratch="$(mktemp -d /var/tmp/repose-debootstrap.XXXXXX)"
  debootstrap --variant=minbase bookworm "$scratch" http://deb.debian.org/debian >/dev/null
  tar -C "$scratch" -cf "$cache.part" .
  mv "$cache.part" "$cache"
  rm -rf "$scratch"
fi

unmount() {
  for m in dev/pts dev/shm dev proc sys; do
    mountpoint -q "$dir/$m" && umount -l "$dir/$m"
  done
  return 0
}
cleanup() {
  unmount
  [ "$keep" -eq 1 ] || rm -rf "$dir"
}
[ -d "$dir" ] && { unmount; rm -rf "$dir"; }
mkdir -p "$dir"
trap cleanup EXIT
tar -C "$dir" -xf "$cache"
# A Debian 12 machine's package sources (main, updates, security) and name resolution, as on this host.
if [ -f /etc/apt/sources.list.d/debian.sources ]; then
  rm -f "$dir/etc/apt/sources.list"
  cp /etc/apt/sources.list.d/debian.sources "$dir/etc/apt/sources.list.d/"
fi
cp /etc/resolv.conf "$dir/etc/resolv.conf"
# debootstrap writes no /etc/hosts; Debian's installer writes this one (the browser test reaches ChromeDriver
# at localhost).
printf '127.0.0.1\tlocalhost\n::1\t\tlocalhost ip6-localhost ip6-loopback\n' >"$dir/etc/hosts"
mount -t proc proc "$dir/proc"
mount -t sysfs sys "$dir/sys"
mount --bind /dev "$dir/dev"
mount --bind /dev/pts "$dir/dev/pts"
mount -t tmpfs shm "$dir/dev/shm"
git clone --quiet "$repo" "$dir/root/repose"

logs="$dir.log"
rm -rf "$logs"
mkdir -p "$logs"
in_root() {  # a login shell of root's, with none of this session's environment
  chroot "$dir" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin /bin/bash -c "$1"
}
timed() {  # timed NAME COMMAND: runs COMMAND in the checkout, prints its exit code and wall time
  local start end rc
  start=$(date +%s)
  set +e
  in_root "cd /root/repose && $2" >"$logs/$1.log" 2>&1
  rc=$?
  set -e
  end=$(date +%s)
  printf '%-28s rc %d in %d min %02d s   (log %s)\n' "$2" "$rc" $(((end - start) / 60)) $(((end - start) % 60)) \
    "$logs/$1.log"
  return "$rc"
}

echo "fresh Debian 12 root $dir, $(nproc) cores, checkout $(git -C "$repo" rev-parse --short HEAD)"
status=0
timed quickstart scripts/quickstart.sh || status=1
if in_root 'cd / && command -v repose && repose --version && python3 -c "import repose, sys; print(repose.__file__)"' \
    >"$logs/check.log" 2>&1 && [ -f "$dir/root/repose/results/paper/report.html" ]; then
  echo "  repose on the PATH, import repose works, results/paper/report.html written: $(tr '\n' ' ' <"$logs/check.log")"
else
  echo "  FAILED: repose on the PATH / import repose / the paper's report ($logs/check.log)"
  status=1
fi
[ "$quickstart_only" -eq 0 ] || exit "$status"
timed test scripts/test.sh || status=1
grep -E "tests passed|tests failed" "$logs/test.log" | sed 's/^/  /' || true
if [ "$ci" -eq 1 ]; then
  timed ci .ci/run || status=1
  grep -E "tests passed|tests failed|^fuzzing" "$logs/ci.log" | sed 's/^/  /' || true
fi
exit "$status"

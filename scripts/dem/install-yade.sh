#!/usr/bin/env bash
# Installs Debian's Yade (2023.02 on Debian 12) unless it is there: what scripts/dem-example.sh and
# scripts/dem-peer.sh need on top of scripts/install-deps.sh (kept out of the quick start). Needs root or sudo.
set -euo pipefail
command -v yade >/dev/null && exit 0
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "Installing Yade (Debian's yade package)"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends yade >/dev/null

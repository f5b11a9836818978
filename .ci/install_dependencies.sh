#!/usr/bin/env bash
# Installs the Debian 12 packages Polycube_IGA needs, only those missing; silent when all
# are there. Needs root (or sudo).
set -euo pipefail
packages=(build-essential cmake libcgal-dev libeigen3-dev libboost-graph-dev libsuitesparse-dev catch2)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}" >&2
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo_cmd apt-get update -qq
$sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null

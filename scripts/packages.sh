# Sourced by the scripts: installMissing PACKAGE... installs the Debian packages that
# are not installed yet (apt-get; sudo unless root), and nothing else.
installMissing() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -gt 0 ] || return 0
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# What the libraries (core, fitting, app/io) need to build.
LAFAIR_LIBRARY_PACKAGES=(cmake ninja-build pkg-config libeigen3-dev libceres-dev nlohmann-json3-dev)

# Shared by the LinuxCNC tests: the environment LinuxCNC's own CI uses to run headless, as root or not.
# rtapi_app refuses to run as root unless RTAPI_UID names the user it acts as; that user must own the directory
# of the FIFO (RTAPI_FIFO_PATH) and of HOME, where LinuxCNC writes its logs.

# Skips (exit 77) unless LinuxCNC's module directory holds exactly the modules of this build.
require_installed_modules() {
  local built=$1 rtlib=${LINUXCNC_RTLIB_DIR:-/usr/lib/linuxcnc/modules} m
  for m in stiffpathkins stiffpathcomp; do
    if ! cmp -s "$built/$m.so" "$rtlib/$m.so"; then
      echo "SKIP: $rtlib/$m.so is not this build's $built/$m.so;"
      echo "      install them with: cmake --build <build dir> --target stiffpath_linuxcnc_install_modules (as root)"
      exit 77
    fi
  done
}

prepare_work_dir() {
  rm -rf "$1"
  mkdir -p "$1/home"
}

hand_over_work_dir() {
  export HOME="$1/home" RTAPI_FIFO_PATH="$1/rtapi_fifo"
  if [ "$(id -u)" -eq 0 ]; then
    export RTAPI_UID=${RTAPI_UID:-65534}
    chown -R "$RTAPI_UID" "$1"
  fi
}

# Shared by the LinuxCNC tests that start its real-time environment.

# Skips (exit 77) unless LinuxCNC's module directory holds exactly the modules of this build.
require_installed_modules() {
  local built=$1 rtlib=${LINUXCNC_RTLIB_DIR:-/usr/lib/linuxcnc/modules} m
  for m in stiffpathkins stiffpathcomp stiffpathlaser; do
    if ! cmp -s "$built/$m.so" "$rtlib/$m.so"; then
      echo "SKIP: $rtlib/$m.so is not this build's $built/$m.so;"
      echo "      install them with: cmake --build <build dir> --target stiffpath_linuxcnc_install_modules (as root)"
      exit 77
    fi
  done
}

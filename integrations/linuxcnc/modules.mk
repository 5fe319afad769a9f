# Builds the real-time modules stiffpathkins.so and stiffpathcomp.so with LinuxCNC's own rules (Makefile.modinc),
# the stiffpath C interface and C++ library linked in statically, and stiffpathlaser.so (plain C).
# Called by CMakeLists.txt in the build directory:
#   make -f modules.mk SRCDIR=... MODINC=.../Makefile.modinc STIFFPATH_INCLUDE=... STIFFPATH_ARCHIVES="a.a b.a" STIFFPATH_LIBS="..."
obj-m := stiffpathkins.o stiffpathcomp.o stiffpathlaser.o
stiffpathkins-objs := stiffpathkins.o $(STIFFPATH_ARCHIVES)
stiffpathcomp-objs := stiffpathcomp.o $(STIFFPATH_ARCHIVES)

include $(MODINC)

vpath %.c $(SRCDIR)
EXTRA_CFLAGS += -I$(STIFFPATH_INCLUDE) -I$(SRCDIR)
# Only the rtapi exports stay global (the .ver script of Makefile.modinc); the C++ runtime comes from the
# shared libstdc++ that rtapi_app already has; every symbol is bound at load time, not in the servo thread.
LDFLAGS += -Wl,--no-as-needed -Wl,-z,now $(STIFFPATH_LIBS)

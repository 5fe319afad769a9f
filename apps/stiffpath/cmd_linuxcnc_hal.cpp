// The HAL files of `stiffpath linuxcnc config`: LinuxCNC's route (machine.hal) and the streamed route (stream.hal).
#include <string>

namespace stiffpath::cli::linuxcnc {

// LinuxCNC plans; stiffpathkins converts, stiffpathcomp corrects, stiffpathlaser drives the laser; simulated drives.
std::string machine_hal() {
  return R"(# HAL of the simulated five-bar: stiffpath's kinematics, motion, the compensation between motion and the drives, the
# laser output. The robot and model come from the INI's [STIFFPATH] section (read by stiffpathkins and stiffpathcomp).
#
# Real drives (docs/linuxcnc.md, "Going to a real machine"): replace the two "simulated drives" lines by the hardware,
# the command in degrees (joint.N.cmd-out) to the drive, its position in degrees back into joint.N.fb-in, e.g.
#   step/dir, parallel port:  loadrt stepgen step_type=0,0 / net j0-drive => stepgen.0.position-cmd /
#                             net j0-drive-fb stepgen.0.position-fb => stiffpathcomp.joint.0.fb-in (base thread ~25 us)
#   Mesa (hostmot2) stepgen:  net j0-drive => hm2_7i96s.0.stepgen.00.position-cmd /
#                             net j0-drive-fb hm2_7i96s.0.stepgen.00.position-fb => stiffpathcomp.joint.0.fb-in
#   servo drives, encoders:   net j0-drive => pid.0.command / encoder position => pid.0.feedback and joint.0.fb-in
#   EtherCAT CiA 402 drives:  net j0-drive => cia402.0.pos-cmd / cia402.0.pos-fb => stiffpathcomp.joint.0.fb-in
# with the drive scaled in degrees of the joint, homed to the angles of [JOINT_N]HOME (switches or absolute encoders),
# and the laser's two signals (laser-enable, laser-power) wired at the end of this file.

loadrt [KINS]KINEMATICS
loadrt [EMCMOT]EMCMOT servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=[KINS]JOINTS
loadrt stiffpathcomp
loadrt stiffpathlaser
loadrt and2 names=all-homed,enable-ok,laser-ok
loadrt not names=no-fault

addf motion-command-handler servo-thread
addf motion-controller servo-thread
# after motion-controller: they read this period's commands
addf stiffpathcomp servo-thread
addf stiffpathlaser servo-thread
addf all-homed servo-thread
addf no-fault servo-thread
addf enable-ok servo-thread
addf laser-ok servo-thread

# The Cartesian command (machine units) for the acceleration estimate
net x-cmd axis.x.pos-cmd => stiffpathcomp.x-cmd
net y-cmd axis.y.pos-cmd => stiffpathcomp.y-cmd

# Joint commands: motion -> compensation -> drive; drive feedback -> compensation -> motion
net j0-motor-cmd joint.0.motor-pos-cmd => stiffpathcomp.joint.0.cmd-in
net j1-motor-cmd joint.1.motor-pos-cmd => stiffpathcomp.joint.1.cmd-in
net j0-pos-cmd joint.0.pos-cmd => stiffpathcomp.joint.0.pos-cmd
net j1-pos-cmd joint.1.pos-cmd => stiffpathcomp.joint.1.pos-cmd
net j0-drive stiffpathcomp.joint.0.cmd-out
net j1-drive stiffpathcomp.joint.1.cmd-out
# simulated drives that follow their command exactly
net j0-drive => stiffpathcomp.joint.0.fb-in
net j1-drive => stiffpathcomp.joint.1.fb-in
net j0-motor-fb stiffpathcomp.joint.0.fb-out => joint.0.motor-pos-fb
net j1-motor-fb stiffpathcomp.joint.1.fb-out => joint.1.motor-pos-fb

# Compensate once the machine knows where it is
net j0-homed joint.0.homed => all-homed.in0
net j1-homed joint.1.homed => all-homed.in1
net compensate all-homed.out => stiffpathcomp.enable

# E-stop chain: a refused step (fault) drops the machine out of enable; resetting E-stop clears the fault
net user-enable iocontrol.0.user-enable-out => enable-ok.in0
net comp-fault stiffpathcomp.fault => no-fault.in
net comp-ok no-fault.out => enable-ok.in1
net emc-enable enable-ok.out => iocontrol.0.emc-enable-in
net estop-reset iocontrol.0.user-request-enable => stiffpathcomp.reset

# Tool changes (none on this machine) complete at once
net tool-prepare iocontrol.0.tool-prepare => iocontrol.0.tool-prepared
net tool-change iocontrol.0.tool-change => iocontrol.0.tool-changed

# The laser: M3/M4/M5 and S through the spindle, M62/M63 P0 through motion's synchronised output 0. stiffpathlaser
# fires only while the tool moves on a feed move or arc, and delays its outputs by the two servo periods that
# motion's joint interpolation and the compensation lag behind the Cartesian command (docs/linuxcnc.md, "The laser").
setp stiffpathlaser.s-max [STIFFPATH]S_MAX
net laser-on spindle.0.on => stiffpathlaser.on
net laser-m4 spindle.0.reverse => stiffpathlaser.dynamic
net laser-s spindle.0.speed-out-abs => stiffpathlaser.s
net laser-m62 motion.digital-out-00 => stiffpathlaser.full
net motion-type motion.motion-type => stiffpathlaser.motion-type
net current-vel motion.current-vel => stiffpathlaser.current-vel
net requested-vel motion.requested-vel => stiffpathlaser.requested-vel
# it may fire while the machine is on and the compensation has not faulted
net comp-ok => laser-ok.in0
net motion-on motion.motion-enabled => laser-ok.in1
net laser-allowed laser-ok.out => stiffpathlaser.gate
# The laser's enable and power (0..1): on a real machine e.g.
#   net laser-enable => parport.0.pin-17-out         (or a Mesa GPIO: hm2_7i96s.0.ssr.00.out-00)
#   net laser-power => pwmgen.0.value                (loadrt pwmgen output_type=0, setp pwmgen.0.scale 1), or a Mesa
#                                                     PWM generator (hm2_….pwmgen.00.value), or an analog output
net laser-enable stiffpathlaser.laser
net laser-power stiffpathlaser.power
)";
}

// stiffpath plans; streamer plays the joint commands and the laser, one line per servo period; motion is not involved.
std::string stream_hal() {
  return R"(# The streamed route: joint commands planned and compensated offline by `stiffpath run`, converted by
# stiffpath-halstream (columns: sample, theta1, theta2 in degrees, laser 0/1, power 0..1), played into the servo
# thread by streamer, one line per period. Motion is not involved. `stiffpath linuxcnc run <folder> JOB --route stiffpath`
# adds the file and a recorder; by hand:
#   stiffpath run JOB --robot <ROBOT> --model <MODEL> --rate <1e9 / SERVO_PERIOD> --format bin -o job.bin
#   stiffpath-halstream job.bin --period-ns <SERVO_PERIOD> -o job.stream
#   halrun -i machine.ini   then: source stream.hal / loadusr halstreamer job.stream / start
# The signals carry the names of machine.hal's: on a real machine j0-drive, j1-drive, laser-enable and laser-power go
# to the same hardware, with the drives enabled and the robot standing at the job's first point before the stream
# starts (or switch the drives between motion and the streamer with a mux2 per joint while motion is idle).

loadrt threads name1=servo-thread period1=[EMCMOT]SERVO_PERIOD fp1=1
loadrt streamer depth=[STREAM]DEPTH cfg=uffbf
addf streamer.0 servo-thread

net stream-sample streamer.0.pin.0
net j0-drive streamer.0.pin.1
net j1-drive streamer.0.pin.2
net laser-enable streamer.0.pin.3
net laser-power streamer.0.pin.4
net stream-underruns streamer.0.underruns
)";
}

}  // namespace stiffpath::cli::linuxcnc

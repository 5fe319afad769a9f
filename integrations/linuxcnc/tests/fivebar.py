"""Forward kinematics of a five-bar robot file, written out here from its geometry (two circles' intersection), so that
the LinuxCNC tests check the library's angles against an independent computation."""
import json
import math


class FiveBar:
    def __init__(self, robot_file):
        with open(robot_file) as f:
            r = json.load(f)
        self.a1, self.a2 = r["left_actuator_mm"], r["right_actuator_mm"]
        self.lp1, self.lp2 = r["left_proximal_mm"], r["right_proximal_mm"]
        self.ld1, self.ld2 = r["left_distal_mm"], r["right_distal_mm"]
        self.home = r.get("home_mm")
        self.joints = r["joints"]

    def forward_mm(self, theta1, theta2, near):
        """The end point (mm) for the joint angles (rad): of the distal circles' two intersections, the one nearer to
        `near` (the assembly mode is the one the robot is in; the other lies far away)."""
        b1 = (self.a1[0] + self.lp1 * math.cos(theta1), self.a1[1] + self.lp1 * math.sin(theta1))
        b2 = (self.a2[0] + self.lp2 * math.cos(theta2), self.a2[1] + self.lp2 * math.sin(theta2))
        dx, dy = b2[0] - b1[0], b2[1] - b1[1]
        d = math.hypot(dx, dy)
        along = (self.ld1 ** 2 - self.ld2 ** 2 + d * d) / (2 * d)
        h = math.sqrt(max(0.0, self.ld1 ** 2 - along ** 2))
        mx, my = b1[0] + along * dx / d, b1[1] + along * dy / d
        candidates = [(mx - h * dy / d, my + h * dx / d), (mx + h * dy / d, my - h * dx / d)]
        return min(candidates, key=lambda p: math.hypot(p[0] - near[0], p[1] - near[1]))

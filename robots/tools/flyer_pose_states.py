#!/usr/bin/env python3
"""The same random body poses as states of dss_free_flyer (floating joint) and of
dss_free_flyer_serial (six joints from a fixed root), as two CSV files for dss_check --states
(stdlib only).

Usage (from the repository root):
  python3 robots/tools/flyer_pose_states.py N SEED OUT_DIR
writes OUT_DIR/floating.csv (base/trans_x ... base/rot_w) and OUT_DIR/serial.csv
(x, y, z, yaw, pitch, roll): N poses with the position uniform in the window scene's room
(x -3 .. 3, y -2 .. 2, z 0 .. 3), yaw and roll uniform in [-pi, pi], pitch in [-pi/2, pi/2];
row k of both files is the same pose, rotation Rz(yaw) Ry(pitch) Rx(roll) and its unit
quaternion (x, y, z, w).
"""
import math
import os
import random
import sys


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    n, seed, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    if n < 1:
        sys.exit("N must be at least 1")
    rng = random.Random(seed)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "serial.csv"), "w") as ser, \
            open(os.path.join(out, "floating.csv"), "w") as flo:
        ser.write("x,y,z,yaw,pitch,roll\n")
        flo.write("base/trans_x,base/trans_y,base/trans_z,"
                  "base/rot_x,base/rot_y,base/rot_z,base/rot_w\n")
        for _ in range(n):
            x, y, z = rng.uniform(-3, 3), rng.uniform(-2, 2), rng.uniform(0, 3)
            yaw = rng.uniform(-math.pi, math.pi)
            pitch = rng.uniform(-math.pi / 2, math.pi / 2)
            roll = rng.uniform(-math.pi, math.pi)
            cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
            cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
            cr, sr = math.cos(roll / 2), math.sin(roll / 2)
            # q = q_z(yaw) q_y(pitch) q_x(roll)
            qw = cy * cp * cr + sy * sp * sr
            qx = cy * cp * sr - sy * sp * cr
            qy = cy * sp * cr + sy * cp * sr
            qz = sy * cp * cr - cy * sp * sr
            ser.write("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n" % (x, y, z, yaw, pitch, roll))
            flo.write("%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n" % (x, y, z, qx, qy, qz, qw))


if __name__ == "__main__":
    main()

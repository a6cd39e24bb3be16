#!/usr/bin/env python3
"""Low-level motor interface: the attributes and commands of one motor, as ev3dev exposes them.

Try it:  ev3sim2d run examples/motor_low_level.py
"""

import time

from ev3dev2.motor import OUTPUT_A, MediumMotor

arm = MediumMotor(OUTPUT_A)
print("driver", arm.driver_name, "max speed", arm.max_speed, "counts per rotation", arm.count_per_rot)

# run to a position relative to where the motor is, then hold it there
arm.run_to_rel_pos(position_sp=180, speed_sp=500, stop_action="hold")
arm.wait_while("running")
print("after run_to_rel_pos:", arm.position, arm.state)

# run for a time, then coast: the shaft rolls on a little after time_sp
arm.run_timed(time_sp=500, speed_sp=-360, stop_action="coast")
arm.wait_while("running")
print("after run_timed:", arm.position)

# drive by duty cycle, changing it while the motor runs
arm.run_direct(duty_cycle_sp=50)
time.sleep(0.2)
arm.duty_cycle_sp = -50
time.sleep(0.2)
arm.stop(stop_action="brake")

# the encoder can be set, and reset clears everything
arm.position = 0
arm.reset()
print("after reset:", arm.position, arm.speed_sp, arm.stop_action)

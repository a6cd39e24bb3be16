"""
The scenarios run through both the real python-ev3dev2 2.1.0 (record_upstream_writes.py) and
our shim (tests/ev3dev2/test_behaviour_conformance.py), each on a fresh FakeBrick.

A scenario is (devices, script): the devices are FakeBrick specs, the script is Python run
with ``record(value)`` (note a value the program saw), ``attempt(action)`` (record what an
action returns or the exception it raises) and ``run_threads_briefly(sleeps)`` (threads the
library starts run at once, in the calling thread, until they have slept that many times:
MoveDifferential's odometry then integrates scripted encoder counts deterministically).
The exception a script lets out ends it and is recorded too.

Changing a scenario means recording the fixture again:
``python tests/ev3dev2/conformance/record_upstream_writes.py``.
"""

from ..fake_brick import battery, leds, lego_port, medium_motor, sensor, tacho_motor


def pair(**attrs):
    return [tacho_motor("motor1", "outB", **attrs), tacho_motor("motor2", "outC", **attrs)]


# One motor-level call (or a few of a kind) per scenario: the writes the motors receive, and the
# exception the call raises.  Speeds are percent unless a unit says otherwise; 'outA' is a lone
# large motor, 'outB'/'outC' a drive pair.
MOTOR = [tacho_motor("motor0", "outA")]
TANK = "from ev3dev2.motor import *\ntank = MoveTank(OUTPUT_B, OUTPUT_C)\n"
STEER = "from ev3dev2.motor import *\nsteer = MoveSteering(OUTPUT_B, OUTPUT_C)\n"
DIFF = "from ev3dev2.motor import *\nfrom ev3dev2.wheel import EV3Tire\ndrive = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3Tire, 128)\n"
ONE = "from ev3dev2.motor import *\nm = LargeMotor(OUTPUT_A)\n"


def one_motor(script):
    return (MOTOR, ONE + script)


def drive_pair(prefix, script, **attrs):
    return (pair(**attrs), prefix + script)


MOTOR_SCENARIOS = {
    # -- a single motor: signs, rounding, brake and coast ---------------------------------
    "motor_on_for_degrees_signs": one_motor(
        "for speed, degrees in ((50, 90), (-50, 90), (50, -90), (-50, -90), (0, 90), (50, 0)):\n"
        "    m.on_for_degrees(speed, degrees, block=False)\n"
    ),
    "motor_on_for_rotations_signs": one_motor(
        "for speed, rotations in ((SpeedRPM(30), 2.5), (SpeedRPS(-1), 0.3), (20, -1.25), (-20, -0.001)):\n"
        "    m.on_for_rotations(speed, rotations, block=False)\n"
    ),
    "motor_on_for_seconds": one_motor(
        "for speed, seconds in ((50, 1.5), (-50, 1.2345), (SpeedDPS(500), 0.0015), (SpeedDPM(9000), 0)):\n"
        "    m.on_for_seconds(speed, seconds, block=False)\n"
    ),
    "motor_on_to_position": one_motor(
        "m.on_to_position(25, 720, block=False)\n"
        "m.on_to_position(-25, -90, brake=False, block=False)\n"
        "m.on_to_position(SpeedRPM(20), 12.7, block=False)\n"
    ),
    "motor_speed_rounding": one_motor(
        "for speed in (SpeedPercent(33.33), SpeedNativeUnits(2.5), SpeedNativeUnits(3.5), SpeedNativeUnits(-2.5),\n"
        "              SpeedRPM(12.345), SpeedDPS(100.5), SpeedRPS(0.0001), 0.05, -0.05):\n"
        "    m.on(speed)\n"
        "for degrees in (45.5, 44.5, 0.4, 0.6, -0.5, 1.5):\n"
        "    m.on_for_degrees(SpeedNativeUnits(100.5), degrees, block=False)\n"
    ),
    "motor_brake_and_coast": one_motor(
        "m.on(50, brake=False)\n"
        "m.off()\n"
        "m.off(brake=False)\n"
        "m.on_for_degrees(50, 90, brake=False, block=False)\n"
        "m.on_for_seconds(50, 1, brake=True, block=False)\n"
        "m.stop()\n"
        "m.stop(stop_action='brake')\n"
    ),
    "motor_on_blocks_when_asked": (
        [tacho_motor("motor0", "outA", state=["", "running", "running", ""])],
        ONE + "m.on(30, block=True)\n",
    ),
    "motor_polarity": one_motor(
        "m.polarity = 'inversed'\n"
        "m.on(20)\n"
        "m.polarity = Motor.POLARITY_NORMAL\n"
        "m.on_for_degrees(-20, 30, block=False)\n"
    ),
    "motor_percent_over_100": one_motor("m.on(101)\n"),
    "motor_percent_under_minus_100": one_motor("m.on_for_degrees(-100.5, 90)\n"),
    "motor_rpm_too_fast": one_motor("m.on_for_rotations(SpeedRPM(200), 1)\n"),
    "motor_dps_too_fast_backwards": one_motor("m.on(SpeedDPS(-7000))\n"),
    "motor_native_units_over_max": one_motor("m.on(SpeedNativeUnits(1051))\n"),
    "motor_native_units_under_minus_max": one_motor("m.on(SpeedNativeUnits(-2000))\n"),
    "motor_speed_sp_out_of_range": one_motor("m.speed_sp = 1100\n"),
    "motor_seconds_negative": one_motor("m.on_for_seconds(50, -0.5)\n"),
    "motor_speed_times_text": one_motor("m.on(SpeedPercent(10) * 'x')\n"),
    # -- MoveTank ------------------------------------------------------------------------
    "tank_on_for_degrees": drive_pair(
        TANK,
        "for left, right, degrees in ((50, 25, 360), (25, 50, 360), (-50, 25, 360), (50, -50, 180), (0, 50, 90),\n"
        "                             (50, 0, 90), (0, 0, 90), (30, 30, -90), (-30, -30, 90), (-30, -30, -90),\n"
        "                             (SpeedRPM(20), SpeedRPM(-60), 0), (SpeedDPS(300), SpeedPercent(10), 45.5)):\n"
        "    tank.on_for_degrees(left, right, degrees, block=False)\n",
    ),
    "tank_on_for_rotations": drive_pair(
        TANK,
        "tank.on_for_rotations(-30, 30, 1.5, brake=False, block=False)\n"
        "tank.on_for_rotations(SpeedRPM(40), SpeedRPM(10), -2, block=False)\n"
        "tank.on_for_rotations(SpeedNativeUnits(333.3), 33.3, 0.123, block=False)\n",
    ),
    "tank_on_for_seconds": drive_pair(
        TANK,
        "tank.on_for_seconds(50, -50, 1.25, block=False)\n"
        "tank.on_for_seconds(SpeedRPM(10), 20, 0.0005, brake=False, block=False)\n",
    ),
    "tank_on_and_off": drive_pair(
        TANK,
        "tank.on(-20, SpeedRPM(70))\ntank.off()\ntank.on(0, 0)\ntank.off(brake=False)\ntank.stop()\n"
        "tank.off(motors=[tank.right_motor], brake=False)\n",
    ),
    "tank_blocking_waits_for_both": drive_pair(
        TANK, "tank.on_for_rotations(20, 20, 1)\n", state=["", "running", "running", "", ""]
    ),
    "tank_polarity": drive_pair(
        TANK,
        "tank.set_polarity('inversed')\ntank.on(10, 10)\ntank.set_polarity('normal', motors=[tank.left_motor])\n",
    ),
    "tank_polarity_invalid": drive_pair(TANK, "tank.set_polarity('backwards')\n"),
    "tank_left_speed_invalid": drive_pair(TANK, "tank.on(101, 10)\n"),
    "tank_right_speed_invalid": drive_pair(TANK, "tank.on_for_degrees(10, SpeedRPM(-300), 90)\n"),
    "tank_native_speed_out_of_range": drive_pair(TANK, "tank.on(SpeedNativeUnits(-1200), 10)\n"),
    "tank_seconds_negative": drive_pair(TANK, "tank.on_for_seconds(10, 10, -1)\n"),
    "tank_medium_motors": (
        [medium_motor("motor1", "outB"), medium_motor("motor2", "outC")],
        "from ev3dev2.motor import *\ntank = MoveTank(OUTPUT_B, OUTPUT_C, motor_class=MediumMotor)\n"
        "tank.on_for_degrees(50, 100, 90, block=False)\n",
    ),
    # -- MoveSteering ----------------------------------------------------------------------
    "steering_on": drive_pair(
        STEER,
        "for speed in (50, SpeedRPM(60), -40):\n"
        "    for steering in (-100, -75, -50, -25, 0, 25, 50, 75, 100, 33.3, -0.5):\n"
        "        steer.on(steering, speed)\n",
    ),
    "steering_on_for": drive_pair(
        STEER,
        "steer.on_for_rotations(-50, 40, 2, block=False)\n"
        "steer.on_for_degrees(10, SpeedRPM(50), 180, block=False)\n"
        "steer.on_for_seconds(-30, 60, 1.5, brake=False, block=False)\n"
        "steer.on_for_degrees(100, -20, -90, block=False)\n",
    ),
    "steering_over_100": drive_pair(STEER, "steer.on(101, 50)\n"),
    "steering_under_minus_100": drive_pair(STEER, "steer.on_for_degrees(-100.5, 50, 90)\n"),
    "steering_speed_invalid": drive_pair(STEER, "steer.on(0, 120)\n"),
    # -- MoveDifferential --------------------------------------------------------------------
    "differential_on_for_distance": drive_pair(
        DIFF,
        "drive.on_for_distance(SpeedRPM(40), 500, block=False)\n"
        "drive.on_for_distance(-30, 120, brake=False, block=False)\n"
        "drive.on_for_distance(30, -120, block=False)\n"
        "drive.on_for_distance(-30, -120, block=False)\n",
    ),
    "differential_arcs": drive_pair(
        DIFF,
        "drive.on_arc_right(SpeedRPM(80), 150, 700, block=False)\n"
        "drive.on_arc_left(30, 200, 300, block=False)\n"
        "drive.on_arc_right(-30, 100, 200, brake=False, block=False)\n"
        "drive.on_arc_left(30, 64, 100, block=False)\n",
    ),
    "differential_arc_too_tight": drive_pair(DIFF, "drive.on_arc_left(30, 50, 100)\n"),
    "differential_turns": drive_pair(
        DIFF,
        "drive.turn_right(SpeedRPM(40), 90, block=False)\n"
        "drive.turn_left(30, 45, block=False)\n"
        "drive.turn_degrees(20, -400, block=False)\n"
        "drive.turn_degrees(20, 720, brake=False, block=False)\n"
        "drive.turn_left(30, -45, block=False)\n"
        "drive.turn_right(30, -90, block=False)\n",
    ),
    "differential_blocking_turn": drive_pair(DIFF, "drive.turn_left(30, 90)\n", state=["", "running", ""]),
    "differential_gyro_missing": drive_pair(DIFF, "drive.turn_right(30, 90, use_gyro=True)\n"),
    "differential_coordinates_need_odometry": drive_pair(DIFF, "drive.on_to_coordinates(30, 100, 100)\n"),
    "differential_angle_needs_odometry": drive_pair(DIFF, "drive.turn_to_angle(30, 100)\n"),
    "differential_on_to_coordinates": drive_pair(
        DIFF,
        "run_threads_briefly(sleeps=5)\n"
        "drive.odometry_start()\n"
        "record([drive.x_pos_mm, drive.y_pos_mm, drive.theta])\n"
        "drive.on_to_coordinates(SpeedRPM(30), 300, 200)\n"
        "drive.odometry_stop()\n",
        position=["0", "50", "100", "150", "200", "250"],
    ),
    "differential_turn_to_angle": drive_pair(
        DIFF,
        "run_threads_briefly(sleeps=4)\n"
        "drive.odometry_start(theta_degrees_start=0, x_pos_start=10, y_pos_start=-20)\n"
        "drive.turn_to_angle(SpeedRPM(30), 180)\n"
        "drive.turn_to_angle(30, -45, brake=False)\n"
        "record([drive.x_pos_mm, drive.y_pos_mm, drive.theta, drive.odometry_thread_run])\n"
        "drive.odometry_stop()\n"
        "record(drive.odometry_thread_run)\n",
        position=["0", "-40", "-80", "-120", "-160"],
    ),
    # -- following a line or a gyro angle ------------------------------------------------------
    "follow_line_lost": (
        pair()
        + [sensor("sensor0", "in3", "lego-ev3-color", value0=["40", "20", "35", "65", "70", "80", "90"])],
        TANK + "from ev3dev2.sensor.lego import ColorSensor\ntank.cs = ColorSensor()\n"
        "tank.follow_line(kp=2, ki=0.1, kd=1, speed=SpeedPercent(25), white=60, off_line_count_max=3)\n",
    ),
    "follow_line_right_edge_for_ms": (
        pair() + [sensor("sensor0", "in3", "lego-ev3-color", value0=["31", "45", "12", "30", "50", "29"])],
        TANK + "from ev3dev2.sensor.lego import ColorSensor\ntank.cs = ColorSensor()\n"
        "tank.follow_line(kp=3.3, ki=0.01, kd=0.7, speed=SpeedRPM(30), target_light_intensity=33.5,\n"
        "                 follow_left_edge=False, sleep_time=0.02, follow_for=follow_for_ms, ms=90)\n",
    ),
    "follow_line_no_sensor": drive_pair(TANK, "tank.follow_line(1, 0, 0, 30)\n"),
    "follow_line_too_fast_raises": (
        pair() + [sensor("sensor0", "in3", "lego-ev3-color", value0=["50", "45", "0"])],
        TANK + "from ev3dev2.sensor.lego import ColorSensor\ntank.cs = ColorSensor()\n"
        "tank.follow_line(kp=30, ki=0, kd=0, speed=SpeedPercent(80))\n",
    ),
    "follow_gyro_angle_for_ms": (
        pair() + [sensor("sensor0", "in2", "lego-ev3-gyro", value0=["0", "1", "3", "-2", "-4", "0", "2"])],
        TANK + "from ev3dev2.sensor.lego import GyroSensor\ntank.gyro = GyroSensor()\n"
        "tank.follow_gyro_angle(kp=5, ki=0.2, kd=1.5, speed=SpeedPercent(30), target_angle=1,\n"
        "                       follow_for=follow_for_ms, ms=55)\n",
    ),
    "follow_gyro_angle_too_fast": (
        pair() + [sensor("sensor0", "in2", "lego-ev3-gyro", value0=["0", "40"])],
        TANK + "from ev3dev2.sensor.lego import GyroSensor\ntank.gyro = GyroSensor()\n"
        "tank.follow_gyro_angle(kp=20, ki=0, kd=0, speed=SpeedPercent(60))\n",
    ),
    "follow_gyro_angle_no_sensor": drive_pair(TANK, "tank.follow_gyro_angle(1, 0, 0, 30)\n"),
    "tank_turn_degrees_no_gyro": drive_pair(TANK, "tank.turn_left(10, 90)\n"),
}


# Devices beyond the motor-level calls, each scenario a script of many calls: every read, write
# and poll, and what the script records, must be the same.
DEVICE_SCENARIOS = {
    "motor_commands": (
        [tacho_motor("motor0", "outA", position="540")],
        """
from ev3dev2.motor import *
m = LargeMotor('outA')
record(str(m))
m.on_for_degrees(SpeedPercent(50), 360, block=False)
m.on_for_degrees(-50, 90, brake=False, block=False)
m.on_for_rotations(SpeedRPM(30), 2.5, block=False)
m.on_for_rotations(SpeedRPS(-1), -0.3, block=False)
m.on_to_position(25, 720, block=False)
m.on_for_seconds(SpeedDPS(500), 1.2345, block=False)
m.on_for_seconds(SpeedDPM(9000), 0.5, brake=False, block=False)
m.on(SpeedNativeUnits(-300))
m.off(brake=False)
m.run_timed(time_sp=500, speed_sp=300)
m.run_direct(duty_cycle_sp=-40)
m.run_forever(speed_sp=100)
m.run_to_abs_pos(position_sp=10)
m.run_to_rel_pos(position_sp=-10, speed_sp=50)
m.stop(stop_action='brake')
m.reset()
m.speed_p = 1000
m.speed_d = 1
m.position_p = 2
m.position_i = 3
m.position_d = 4
m.ramp_up_sp = 100
m.ramp_down_sp = 200
m.polarity = 'inversed'
m.position = 7
m.duty_cycle_sp = 20
for name in ('speed_i', 'state', 'rotations', 'degrees', 'polarity', 'ramp_down_sp', 'commands', 'stop_actions',
             'driver_name', 'address', 'count_per_rot', 'duty_cycle', 'duty_cycle_sp', 'position_sp', 'speed',
             'speed_sp', 'time_sp', 'stop_action', 'max_speed', 'position_p', 'speed_p', 'is_running',
             'is_ramping', 'is_holding', 'is_overloaded', 'is_stalled', 'max_rps', 'max_rpm', 'max_dps', 'max_dpm',
             'device_index'):
    record([name, getattr(m, name)])
attempt(lambda: m.on_for_seconds(50, -1))
attempt(lambda: m.count_per_m)
attempt(lambda: setattr(m, 'speed_sp', 2000))
attempt(lambda: m.command)
attempt(lambda: SpeedPercent(101))
attempt(lambda: m.on(SpeedRPM(200)))
attempt(lambda: m.on(SpeedNativeUnits(1051)))
attempt(lambda: m.on(-101))
attempt(lambda: LargeMotor('outD'))
attempt(lambda: str(SpeedPercent(30)) + '|' + str(SpeedPercent(30, 'x')) + '|' + str(SpeedRPM(3)))
attempt(lambda: (SpeedPercent(20) * 2).percent)
""",
    ),
    "motor_blocking": (
        [tacho_motor("motor0", "outA", state=["", "running", "running", "", "", ""])],
        """
from ev3dev2.motor import *
m = LargeMotor('outA')
m.on_for_degrees(50, 90)
m.on_for_rotations(10, 1)
m.on_to_position(10, 0)
m.on_for_seconds(10, 0.5)
m.on(10, block=True)
record(m.wait_while('running', timeout=250))
record(m.wait_until('stalled', timeout=0))
""",
    ),
    "motor_wait_timeout": (
        [tacho_motor("motor0", "outA", state="running stalled")],
        """
from ev3dev2.motor import *
m = Motor('outA')
record(m.wait_while('running', timeout=250))
record(m.wait_until('running', timeout=250))
record(m.wait_until_not_moving(timeout=1000))
""",
    ),
    "medium_and_other_motors": (
        [
            medium_motor("motor0", "outA"),
            {
                "class": "dc-motor",
                "name": "motor1",
                "attrs": {
                    "address": "ev3-ports:outC",
                    "command": "",
                    "time_sp": "0",
                    "duty_cycle_sp": "0",
                    "ramp_up_sp": "0",
                    "stop_action": "",
                    "commands": "run-forever stop",
                    "stop_actions": "coast brake",
                    "state": "running",
                    "polarity": "normal",
                    "driver_name": "rcx-motor",
                },
            },
            {
                "class": "servo-motor",
                "name": "motor2",
                "attrs": {
                    "address": "ev3-ports:outD",
                    "command": "",
                    "position_sp": "0",
                    "rate_sp": "0",
                    "max_pulse_sp": "2400",
                    "mid_pulse_sp": "1500",
                    "min_pulse_sp": "600",
                    "polarity": "normal",
                    "state": "",
                    "driver_name": "servo",
                },
            },
        ],
        """
from ev3dev2.motor import *
MediumMotor('outA').on(SpeedPercent(10))
attempt(lambda: LargeMotor('outA'))
attempt(lambda: ActuonixL1250Motor('outA'))
dc = DcMotor('outC')
dc.run_timed(time_sp=100, duty_cycle_sp=50)
dc.run_direct()
dc.run_forever(ramp_up_sp=10)
dc.stop()
dc.stop_action = 'brake'
dc.polarity = 'inversed'
attempt(lambda: dc.stop_action)
record([dc.commands, dc.stop_actions, dc.state, dc.driver_name, dc.address, dc.time_sp, dc.duty_cycle_sp])
servo = ServoMotor('outD')
servo.run(position_sp=-30)
servo.float()
servo.rate_sp = 500
servo.mid_pulse_sp = 1400
record([servo.max_pulse_sp, servo.mid_pulse_sp, servo.min_pulse_sp, servo.position_sp, servo.rate_sp,
        servo.state, servo.polarity, servo.driver_name, servo.address])
record(sorted(m.address for m in list_motors()))
""",
    ),
    "tank": (
        pair(),
        """
from ev3dev2.motor import *
tank = MoveTank('outB', 'outC')
tank.on_for_degrees(SpeedPercent(50), SpeedPercent(25), 360, block=False)
tank.on_for_degrees(0, 0, 360, block=False)
tank.on_for_degrees(SpeedRPM(20), SpeedRPM(-60), 0, block=False)
tank.on_for_rotations(-30, 30, 1.5, brake=False, block=False)
tank.on(-20, SpeedRPM(70))
tank.on_for_seconds(30, 30, 2, block=False)
tank.off(brake=False)
tank.stop()
tank.run_timed(time_sp=100, speed_sp=200)
tank.run_forever(motors=[tank.left_motor], speed_sp=10)
tank.set_args(speed_sp=5)
tank.set_polarity('inversed')
record(tank.is_running)
record(tank.is_holding)
tank.wait_until_not_moving()
tank.reset()
record(str(tank))
attempt(lambda: tank.on_for_seconds(10, 10, -1))
attempt(lambda: tank.on(10, 200))
attempt(lambda: tank.set_polarity('backwards'))
reversed_tank = MoveTank('outC', 'outB', desc='reversed')
reversed_tank.on(10, 20)
record(str(reversed_tank))
""",
    ),
    "tank_blocking": (
        pair(state=["running", ""]),
        """
from ev3dev2.motor import *
tank = MoveTank('outB', 'outC')
tank.on_for_degrees(50, 50, 90)
tank.on_for_seconds(50, 50, 1)
""",
    ),
    "steering": (
        pair(),
        """
from ev3dev2.motor import *
steer = MoveSteering('outB', 'outC')
steer.on_for_rotations(-50, SpeedPercent(40), 2, block=False)
for steering in (0, 25, -25, 100, -100, 75, 33.3):
    steer.on(steering, 50)
    record(steer.get_speed_steering(steering, SpeedRPM(60)))
steer.on_for_degrees(10, SpeedRPM(50), 180, block=False)
steer.on_for_seconds(-30, 60, 1.5, brake=False, block=False)
attempt(lambda: steer.on(101, 50))
""",
    ),
    "differential": (
        pair(),
        """
from ev3dev2.motor import *
from ev3dev2.wheel import EV3Tire, EV3EducationSetTire
drive = MoveDifferential('outB', 'outC', EV3Tire, 128)
drive.on_for_distance(SpeedRPM(40), 500, block=False)
drive.on_for_distance(-30, 120, brake=False, block=False)
drive.turn_right(SpeedRPM(40), 90, block=False)
drive.turn_left(30, 45, block=False)
drive.turn_degrees(20, -400, block=False)
drive.on_arc_right(SpeedRPM(80), 150, 700, block=False)
drive.on_arc_left(30, 200, 300, block=False)
attempt(lambda: drive.on_arc_left(30, 50, 100))
attempt(lambda: drive.on_to_coordinates(30, 100, 100))
attempt(lambda: drive.turn_to_angle(30, 100))
attempt(lambda: drive.turn_right(30, 90, use_gyro=True))
other = MoveDifferential('outB', 'outC', EV3EducationSetTire, 114.5)
other.on_arc_right(50, 100, 250, block=False)
record([other.circumference_mm, other.min_circle_radius_mm, other.theta])
""",
    ),
    "joystick": (
        pair(),
        """
from ev3dev2.motor import *
stick = MoveJoystick('outB', 'outC')
for x, y in ((0, 100), (100, 0), (0, -50), (-100, 0), (30, 40), (-70, 70), (12, -99), (0.5, 0.5)):
    stick.on(x, y)
stick.on(1, 0.5, radius=1)
stick.on(0, 0)
for step in range(17):
    record(MoveJoystick.angle_to_speed_percentage(step * 22.5))
attempt(lambda: MoveJoystick.angle_to_speed_percentage(361))
""",
    ),
    "follow_line": (
        pair()
        + [
            sensor(
                "sensor0",
                "in1",
                "lego-ev3-color",
                mode="COL-COLOR",
                value0=["30", "20", "35", "80", "80", "80"],
            )
        ],
        """
from ev3dev2.motor import *
from ev3dev2.sensor.lego import ColorSensor
tank = MoveTank('outB', 'outC')
attempt(lambda: tank.follow_line(1, 0, 0, 30))
tank.cs = ColorSensor()
attempt(lambda: tank.follow_line(kp=2, ki=0.5, kd=1, speed=SpeedPercent(20), white=60, off_line_count_max=3,
                                 follow_left_edge=False))
""",
    ),
    "follow_line_for_ms": (
        pair() + [sensor("sensor0", "in1", "lego-ev3-color", value0=["30", "28", "33", "31"])],
        """
from ev3dev2.motor import *
from ev3dev2.sensor.lego import ColorSensor
tank = MoveTank('outB', 'outC')
tank.cs = ColorSensor()
tank.follow_line(kp=1.5, ki=0.1, kd=2, speed=20, target_light_intensity=30, sleep_time=0.01,
                 follow_for=follow_for_ms, ms=100)
record(tank.stopwatch)
""",
    ),
    "follow_line_too_fast": (
        pair() + [sensor("sensor0", "in1", "lego-ev3-color", value0=["50", "0"])],
        """
from ev3dev2.motor import *
from ev3dev2.sensor.lego import ColorSensor
tank = MoveTank('outB', 'outC')
tank.cs = ColorSensor()
attempt(lambda: tank.follow_line(kp=100, ki=0, kd=0, speed=SpeedPercent(90)))
""",
    ),
    "follow_gyro_and_turn": (
        pair()
        + [
            sensor(
                "sensor0",
                "in2",
                "lego-ev3-gyro",
                value0=["0", "2", "-3", "5", "0", "0", "10", "25", "29", "29", "20", "-2"],
            )
        ],
        """
from ev3dev2.motor import *
from ev3dev2.sensor.lego import GyroSensor
tank = MoveTank('outB', 'outC')
attempt(lambda: tank.follow_gyro_angle(1, 0, 0, 20))
tank.gyro = GyroSensor()
counter = {'n': 0}
def three_times(tank, times):
    counter['n'] += 1
    return counter['n'] <= times
tank.follow_gyro_angle(kp=3, ki=0.5, kd=1, speed=20, target_angle=0, follow_for=three_times, times=3)
tank.turn_right(SpeedPercent(10), 30)
tank.turn_left(SpeedPercent(10), 30, brake=False, error_margin=3)
""",
    ),
    "differential_with_gyro": (
        pair() + [sensor("sensor0", "in2", "lego-ev3-gyro", value0=["0", "0", "85", "85", "90"])],
        """
from ev3dev2.motor import *
from ev3dev2.sensor.lego import GyroSensor
from ev3dev2.wheel import EV3Tire
drive = MoveDifferential('outB', 'outC', EV3Tire, 128)
drive.gyro = GyroSensor()
drive.turn_right(20, 90, use_gyro=True)
""",
    ),
    "color_sensor": (
        [
            sensor(
                "sensor0",
                "in1",
                "lego-ev3-color",
                mode="COL-COLOR",
                value0=["42", "42", "7", "5", "5", "10"],
                value1="150",
                value2="300",
                num_values="3",
                bin_data_format="u16",
                bin_data="\x0a\x00\x96\x00\x2c\x01",
            )
        ],
        """
from ev3dev2.sensor.lego import ColorSensor
from ev3dev2.sensor import INPUT_1
cs = ColorSensor('in1')
for name in ('reflected_light_intensity', 'reflected_light_intensity', 'ambient_light_intensity', 'color',
             'color_name', 'raw', 'rgb'):
    record([name, getattr(cs, name)])
cs.calibrate_white()
for name in ('rgb', 'lab', 'hsv', 'hls', 'red', 'green', 'blue', 'mode', 'modes', 'num_values', 'decimals', 'units',
             'driver_name', 'address', 'commands', 'bin_data_format', 'device_index'):
    record([name, getattr(cs, name)])
record(list(cs.bin_data()))
record(cs.bin_data('<HHH'))
record(cs.value(1))
cs.mode = 'RGB-RAW'
cs.command = 'x'
attempt(lambda: cs.command)
attempt(lambda: setattr(cs, 'red_maxx', 1))
""",
    ),
    "ultrasonic_sensor": (
        [sensor("sensor0", "in4", "lego-ev3-us", value0="123", decimals="1")],
        """
from ev3dev2.sensor.lego import UltrasonicSensor
us = UltrasonicSensor()
for name in ('distance_centimeters', 'distance_centimeters_continuous', 'distance_centimeters_ping',
             'distance_inches', 'distance_inches_ping', 'distance_inches_continuous', 'other_sensor_present'):
    record([name, getattr(us, name)])
""",
    ),
    "gyro_sensor": (
        [
            sensor(
                "sensor0",
                "in2",
                "lego-ev3-gyro",
                value0=[
                    "7",
                    "15",
                    "0",
                    "0",
                    "3",
                    "-12",
                    "-30",
                    "40",
                    "44",
                    "0",
                    "-6",
                    "-12",
                    "-10",
                    "-8",
                    "-6",
                ],
                value1="-3",
            )
        ],
        """
from ev3dev2.sensor.lego import GyroSensor
gyro = GyroSensor()
for name in ('angle', 'rate', 'angle_and_rate', 'tilt_angle', 'tilt_rate'):
    record([name, getattr(gyro, name)])
gyro.reset()
record(gyro.circle_angle())
gyro.calibrate()
gyro.mode = 'GYRO-ANG'
gyro.wait_until_angle_changed_by(10)
gyro.wait_until_angle_changed_by(-5, direction_sensitive=True)
gyro.wait_until_angle_changed_by(3, direction_sensitive=True)
gyro.mode = 'GYRO-RATE'
attempt(lambda: gyro.wait_until_angle_changed_by(10))
""",
    ),
    "touch_sensor": (
        [sensor("sensor0", "in1", "lego-ev3-touch", value0=["0", "0", "1", "1", "0", "0", "1", "1", "0"])],
        """
from ev3dev2.sensor.lego import TouchSensor
touch = TouchSensor()
record(touch.wait_for_pressed())
record([touch.is_pressed, touch.is_released])
record(touch.wait_for_released(timeout_ms=50))
record(touch.wait_for_bump(timeout_ms=1000, sleep_ms=20))
record(touch.wait_for_pressed(timeout_ms=30, sleep_ms=15))
""",
    ),
    "remote_controlled_tank": (
        pair()
        + [
            sensor(
                "sensor0", "in4", "lego-ev3-ir", mode="IR-REMOTE", value0=["1", "1", "5", "0", "3", "4", "0"]
            )
        ],
        """
from ev3dev2.control.rc_tank import RemoteControlledTank
from ev3dev2.motor import OUTPUT_B, OUTPUT_C
tank = RemoteControlledTank(OUTPUT_B, OUTPUT_C, speed=300)
record([tank.speed_sp, tank.channel])
for _ in range(6):
    tank.remote.process()
""",
    ),
    "infrared_sensor": (
        [
            sensor(
                "sensor0",
                "in3",
                "lego-ev3-ir",
                value0=["4", "9", "1", "1", "0"],
                value1="9",
                value2="-12",
                value3="-128",
                value4="3",
            )
        ],
        """
from ev3dev2.sensor.lego import InfraredSensor
ir = InfraredSensor()
record(ir.proximity)
for channel in (1, 2, 3, 4):
    record([ir.heading(channel), ir.distance(channel), ir.heading_and_distance(channel)])
ir.on_channel1_top_left = lambda state: record(['top_left', state])
ir.on_channel2_beacon = lambda state: record(['beacon', state])
ir.on_change = lambda changes: record(changes)
for _ in range(3):
    ir.process()
for channel in (1, 2, 3, 4):
    record([ir.buttons_pressed(channel), ir.top_left(channel), ir.bottom_left(channel), ir.top_right(channel),
            ir.bottom_right(channel), ir.beacon(channel)])
attempt(lambda: ir.heading(5))
""",
    ),
    "nxt_sensors": (
        [
            sensor("sensor0", "in1", "lego-nxt-sound", mode="DB", modes="DB DBA", value0="512", decimals="1"),
            sensor(
                "sensor1",
                "in2",
                "lego-nxt-light",
                mode="REFLECT",
                modes="REFLECT AMBIENT",
                value0="456",
                decimals="1",
            ),
        ],
        """
from ev3dev2.sensor.lego import SoundSensor, LightSensor
from ev3dev2.sensor import Sensor, list_sensors
sound, light = SoundSensor(), LightSensor()
record([sound.sound_pressure, sound.sound_pressure_low, light.reflected_light_intensity,
        light.ambient_light_intensity])
record(sorted(s.device_index for s in list_sensors()))  # listing order is the folder's
record(Sensor('in2').value())
""",
    ),
    "leds": (
        leds(),
        """
from ev3dev2.led import Leds, Led
lights = Leds()
lights.set_color('LEFT', 'AMBER')
lights.set_color('RIGHT', 'ORANGE', pct=0.5)
lights.set_color('RIGHT', (0.2, 1))
lights.all_off()
lights.reset()
lights.set('LEFT', brightness_pct=0.5)
attempt(lambda: lights.set_color('LEFT', 'PINK'))
attempt(lambda: lights.set_color('MIDDLE', 'RED'))
attempt(lambda: lights.set('MIDDLE', brightness=1))
lights.animate_flash('RED', sleeptime=0.5, duration=2)
lights.animate_police_lights('RED', 'GREEN', duration=1)
lights.animate_cycle(('RED', 'GREEN', 'AMBER'), duration=1)
lights.animate_rainbow(duration=0.5)
led = lights.leds['green_right']
record([str(led), led.max_brightness, led.brightness, led.brightness_pct, led.triggers])
""",
    ),
    "power_and_port": (
        [battery(), lego_port("port0", "in1"), lego_port("port1", "outA")],
        """
from ev3dev2.power import PowerSupply
from ev3dev2.port import LegoPort
power = PowerSupply()
for name in ('measured_current', 'measured_voltage', 'measured_amps', 'measured_volts', 'max_voltage', 'min_voltage',
             'technology', 'type'):
    record([name, getattr(power, name)])
port = LegoPort('in1')
record([port.address, port.driver_name, port.modes, port.mode, port.status])
port.mode = 'nxt-analog'
port.set_device = 'lego-nxt-touch'
attempt(lambda: port.set_device)
record(port.modes)
record(str(LegoPort('outA')))
""",
    ),
    "devices": (
        pair() + [sensor("sensor0", "in1", "lego-ev3-touch")],
        """
import ev3dev2
from ev3dev2 import Device, list_devices, list_device_names
d = Device('tacho-motor', address='outC')
record([str(d), d.device_index])
record(sorted(list_device_names(Device.DEVICE_ROOT_PATH + '/tacho-motor', 'motor*', address=['outB', 'outC'])))
record(sorted(x.device_index for x in list_devices('tacho-motor', '*')))
record(str(Device('lego-sensor', 'sensor*')))
attempt(lambda: Device('lego-sensor', 'sensor*', driver_name='nope'))
record(ev3dev2.library_load_warning_message('x', 'Y'))
""",
    ),
}


SCENARIOS = {**MOTOR_SCENARIOS, **DEVICE_SCENARIOS}

"""One simulated robot: its description, its body in the physics world, its devices and brick.

Each tick the wheel motors plan how far they turn; the robot turns that into
a body velocity (infinite acceleration), the physics moves it, and the
encoders count how far each wheel really went: the forward travel of the
point where the wheel touches the floor.  A robot held by a wall therefore
sees its encoders stop, and its motors report stalled.  While it touches another
robot it also says how hard its wheels push and hold (physics.py settles the
push), so a robot pushed back counts its wheels turning back.

Its sound sensor hears the other robots' speakers (`sound_level`): each robot
knows the others (`others`, set by the Simulation) and its speaker's volume.
"""

from __future__ import annotations

import math

from ..devices.brick import Brick
from ..devices.color import ColorSensor
from ..devices.motor import TachoMotor
from ..devices.nxt_sound import QUIET_PCT, SOUND_REF_CM, SPEAKER_PCT
from ..devices.registry import SENSORS
from ..devices.touch import DEFAULT_BUMPER_CM
from ..world.pose import Pose
from ..world.robot_spec import RobotSpec
from .physics import BRAKE_PCT, COAST_PCT, HOLD_PCT, Physics


def body_outline(spec: RobotSpec) -> list[tuple[float, float]]:
    """The robot's footprint (cm, robot frame): its body box plus the touch sensors' bumpers (each a
    segment `bumper_cm` wide across the direction it faces, at the sensor)."""
    b = spec.body
    half = b.width_cm / 2
    points = [(b.front_cm, -half), (b.front_cm, half), (-b.back_cm, half), (-b.back_cm, -half)]
    for sensor in spec.sensors:
        if sensor.kind == "touch":
            a = math.radians(sensor.angle_deg)
            x, y = sensor.radius_cm * math.cos(a), sensor.radius_cm * math.sin(a)
            facing = math.radians(sensor.aim_deg)  # (as sensor_pose: the heading turned by aim_deg)
            side = float(sensor.options.get("bumper_cm", DEFAULT_BUMPER_CM)) / 2
            dx, dy = -side * math.sin(facing), side * math.cos(facing)
            points += [(x - dx, y - dy), (x + dx, y + dy)]
    return points


class Robot:
    """A robot in the world: pose, wheels, devices; the Surroundings its sensors measure."""

    def __init__(
        self, name: str, spec: RobotSpec, start: Pose, physics: Physics, floor, rng, ambient: float
    ) -> None:
        self.name = name
        self.spec = spec
        self.start = start
        self.physics = physics
        self.rng = rng
        self.tick = 0
        self.sound_until_tick = 0  # the brick's speaker plays until this tick
        self.sound_volume = 100.0  # its speaker's volume, % (the Simulation follows the brick's sounds)
        self.others: list[Robot] = []  # the other robots in the world, whose sounds it hears
        heading = math.radians(start.heading_deg)
        self.body = physics.add_robot(body_outline(spec), start.x_cm, start.y_cm, heading)
        self.group = self.body.group
        # cone(x, y, direction, half_rad, max_cm): the nearest wall or other robot in a sensor's cone
        self.cone = physics.cone_query(self.group)
        self.x, self.y, self.heading_rad = start.x_cm, start.y_cm, heading
        self.turn_rate = 0.0
        self.cm_per_deg = math.pi * spec.wheel_diameter_mm / 10.0 / 360.0
        self.track_cm = spec.axle_track_mm / 10.0

        self.motors: dict[str, TachoMotor] = {}
        for m in sorted(spec.motors, key=lambda m: m.port):
            self.motors[m.port] = TachoMotor(f"ev3-ports:{m.port}", m.kind, m.limits_deg, m.load_pct)
        self.left = self.motors[spec.left_wheel.port]
        self.right = self.motors[spec.right_wheel.port]
        # a motor mounted the other way round turns its wheel backwards: -1
        self.left_mount = -1.0 if spec.left_wheel.reversed else 1.0
        self.right_mount = -1.0 if spec.right_wheel.reversed else 1.0
        self.other_motors = [m for m in self.motors.values() if m is not self.left and m is not self.right]

        self.sensors = {}
        for s in sorted(spec.sensors, key=lambda s: s.port):
            kind = SENSORS[s.kind]
            address = f"ev3-ports:{s.port}"
            if issubclass(kind, ColorSensor):
                self.sensors[s.port] = kind(address, s, self, floor, ambient)
            else:
                self.sensors[s.port] = kind(address, s, self)
        self.brick = Brick(list(self.motors.values()), list(self.sensors.values()))
        self._planned = (0.0, 0.0)

    # ------------------------------------------------------------ surroundings
    def sensor_pose(self, mount: tuple[float, float, float]) -> tuple[float, float, float]:
        """Where a sensor mounted at (radius cm, angle rad, aim rad) is, and the direction it looks."""
        radius, angle, aim = mount
        h = self.heading_rad
        return self.x + radius * math.cos(h + angle), self.y + radius * math.sin(h + angle), h + aim

    def ray(self, x: float, y: float, direction: float, max_cm: float) -> float | None:
        return self.physics.ray(x, y, direction, max_cm, self.group)

    def near(self, x: float, y: float, reach_cm: float) -> bool:
        return self.physics.near(x, y, reach_cm, self.group)

    def touches_segment(self, x0: float, y0: float, x1: float, y1: float, reach_cm: float) -> bool:
        return self.physics.touches_segment(x0, y0, x1, y1, reach_cm, self.group)

    def sounding(self) -> bool:
        """Whether the brick's speaker plays now."""
        return self.sound_until_tick > self.tick

    def sound_level(self, x: float, y: float) -> float:
        """The sound level (%) at (x, y) on this robot: the quiet room or its own speaker, plus each
        other robot's speaker playing, by the inverse square of the distance to it."""
        level = SPEAKER_PCT if self.sounding() else QUIET_PCT
        for other in self.others:
            if other.sounding():
                d2 = max((other.x - x) ** 2 + (other.y - y) ** 2, SOUND_REF_CM**2)
                level += SPEAKER_PCT * other.sound_volume / 100.0 * SOUND_REF_CM**2 / d2
        return min(level, 100.0)

    def driving(self) -> bool:
        """Whether the wheel motors are still being driven (they keep going after a program ends)."""
        return any(
            m.mode not in ("stopped", "coast") and abs(m.plan(0.01)) > 1e-6 for m in (self.left, self.right)
        )

    # ------------------------------------------------------------------ ticks
    def before_step(self, dt: float) -> None:
        """Set the body's velocity from what the wheel motors plan to turn this tick."""
        left = self.left.plan(dt)
        right = self.right.plan(dt)
        self._planned = (left, right)
        left_cm = left * self.left_mount * self.cm_per_deg
        right_cm = right * self.right_mount * self.cm_per_deg
        turn = (right_cm - left_cm) / self.track_cm
        if self.body.robots_touching:
            self._push_and_hold(left, right, dt)
        # velocity along the mid-step heading: arcs come out right to second order
        self.body.drive((left_cm + right_cm) / 2 / dt, self.heading_rad + turn / 2, turn / dt)

    def _push_and_hold(self, left: float, right: float, dt: float) -> None:
        """How hard the wheels push (a driven wheel motor: the power it runs at, % of its full
        speed) and hold (a stopped one: by its stop action), for physics' push between robots."""
        push = hold = 0.0
        for motor, planned in ((self.left, left), (self.right, right)):
            if motor.mode == "coast":  # rolling out: only the gears' friction
                hold += COAST_PCT
            elif planned:
                push += 100.0 * abs(planned) / (motor.max_speed * dt)
            elif motor.mode == "stopped":
                hold += {"hold": HOLD_PCT, "brake": BRAKE_PCT}.get(motor.stop_action, COAST_PCT)
            else:  # driven at speed 0: the speed PID holds it
                hold += HOLD_PCT
        self.body.push_pct, self.body.hold_pct = push, hold

    def place(self, x_cm: float, y_cm: float, heading_deg: float) -> float:
        """Pick the robot up and put it down at (x, y), facing heading_deg (a live run's drag).  The
        encoders and the gyro do not know: they count on from where they were.  The turn, in radians."""
        turn = (math.radians(heading_deg) - self.heading_rad + math.pi) % (2 * math.pi) - math.pi
        heading = self.heading_rad + turn
        self.body.place(x_cm, y_cm, heading)
        self.x, self.y, self.heading_rad = x_cm, y_cm, heading
        self.turn_rate = 0.0
        for sensor in self.sensors.values():
            if hasattr(sensor, "zero_rad"):  # a gyro: it counts from its zero, which turns with the robot
                sensor.zero_rad += turn
        return turn

    def after_step(self, dt: float) -> None:
        """Read back where the body went; the encoders count each wheel's real forward travel."""
        x, y, heading = self.body.pose()
        dx, dy = x - self.x, y - self.y
        dh = heading - self.heading_rad
        mid = self.heading_rad + dh / 2
        forward = dx * math.cos(mid) + dy * math.sin(mid)
        half_turn = dh * self.track_cm / 2
        planned_left, planned_right = self._planned
        self.left.measured(planned_left, self.left_mount * (forward - half_turn) / self.cm_per_deg, dt)
        self.right.measured(planned_right, self.right_mount * (forward + half_turn) / self.cm_per_deg, dt)
        for motor in self.other_motors:  # an arm, a gripper: against its end stops and load, if any
            if motor.mode != "stopped" or motor.speed_dps:
                motor.turn_free(dt)
        self.turn_rate = dh / dt
        self.x, self.y, self.heading_rad = x, y, heading
        self.tick += 1

"""A tank driven by the EV3 infrared remote (python-ev3dev2 2.1.0): each lever turns one motor."""

import logging
import time
from time import sleep  # noqa: F401  (only for star imports; the shim calls time.sleep, which a run replaces)

from ev3dev2.motor import MoveTank
from ev3dev2.sensor.lego import InfraredSensor

log = logging.getLogger(__name__)


class RemoteControlledTank(MoveTank):
    """
    A MoveTank whose motors follow the infrared remote's levers on ``channel``:
    the left levers (red buttons) drive the left motor, the right levers (blue
    buttons) the right one, at ``speed`` (native units) while pressed.
    """

    def __init__(self, left_motor_port, right_motor_port, polarity="inversed", speed=400, channel=1):
        MoveTank.__init__(self, left_motor_port, right_motor_port)
        self.set_polarity(polarity)

        left_motor = self.motors[left_motor_port]
        right_motor = self.motors[right_motor_port]
        self.speed_sp = speed
        self.remote = InfraredSensor()
        self.remote.on_channel1_top_left = self.make_move(left_motor, self.speed_sp)
        self.remote.on_channel1_bottom_left = self.make_move(left_motor, self.speed_sp * -1)
        self.remote.on_channel1_top_right = self.make_move(right_motor, self.speed_sp)
        self.remote.on_channel1_bottom_right = self.make_move(right_motor, self.speed_sp * -1)
        self.channel = channel

    def make_move(self, motor, dc_sp):
        """A remote-button handler: run ``motor`` at ``dc_sp`` while pressed, stop it when released."""

        def move(state):
            if state:
                motor.run_forever(speed_sp=dc_sp)
            else:
                motor.stop()

        return move

    def main(self):
        """Follow the remote forever; any error stops the motors (and is logged)."""
        try:
            while True:
                self.remote.process()
                time.sleep(0.01)

        # Exit cleanly so that all motors are stopped
        except (KeyboardInterrupt, Exception) as e:
            log.exception(e)
            self.off()

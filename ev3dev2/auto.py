"""Everything at once (python-ev3dev2 2.1.0): ``from ev3dev2.auto import *``."""

from ev3dev2 import *  # noqa: F403
from ev3dev2._platform.ev3 import (  # noqa: F401
    INPUT_1,
    INPUT_2,
    INPUT_3,
    INPUT_4,
    LED_COLORS,
    LED_GROUPS,
    LEDS,
    OUTPUT_A,
    OUTPUT_B,
    OUTPUT_C,
    OUTPUT_D,
)
from ev3dev2.button import *  # noqa: F403
from ev3dev2.console import *  # noqa: F403
from ev3dev2.display import *  # noqa: F403
from ev3dev2.fonts import *  # noqa: F403
from ev3dev2.led import *  # noqa: F403
from ev3dev2.motor import *  # noqa: F403
from ev3dev2.port import *  # noqa: F403
from ev3dev2.power import *  # noqa: F403
from ev3dev2.sensor import *  # noqa: F403
from ev3dev2.sensor.lego import *  # noqa: F403
from ev3dev2.sound import *  # noqa: F403

platform = get_current_platform()  # noqa: F405
if platform == "fake":
    from ev3dev2._platform.fake import (  # noqa: F401
        INPUT_1,
        INPUT_2,
        INPUT_3,
        INPUT_4,
        LED_COLORS,
        LED_GROUPS,
        LEDS,
        OUTPUT_A,
        OUTPUT_B,
        OUTPUT_C,
        OUTPUT_D,
    )

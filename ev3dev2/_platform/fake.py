"""Port names of the 'fake' platform, a computer without a brick's board (FAKE_SYS set, or no
/sys/class/board-info/) (as python-ev3dev2 2.1.0).

The simulated brick is an EV3, so the library uses these names only when the environment sets
FAKE_SYS, as python-ev3dev2's own tests do (get_current_platform() then says 'fake').
"""

OUTPUT_A = "outA"
OUTPUT_B = "outB"
OUTPUT_C = "outC"
OUTPUT_D = "outD"

INPUT_1 = "in1"
INPUT_2 = "in2"
INPUT_3 = "in3"
INPUT_4 = "in4"

BUTTONS_FILENAME = None
EVDEV_DEVICE_NAME = None

LEDS = {}
LED_GROUPS = {}
LED_COLORS = {}
LED_DEFAULT_COLOR = ""

"""Port names and buttons of the FatcatLab EVB (and QuestCape) (as python-ev3dev2 2.1.0).

A program on the simulated EV3 may import it, as on a real EV3; get_current_platform() says 'ev3', so the
library itself never uses it.
"""

OUTPUT_A = "outA"
OUTPUT_B = "outB"
OUTPUT_C = "outC"
OUTPUT_D = "outD"

INPUT_1 = "in1"
INPUT_2 = "in2"
INPUT_3 = "in3"
INPUT_4 = "in4"

BUTTONS_FILENAME = "/dev/input/by-path/platform-evb-buttons-event"
EVDEV_DEVICE_NAME = "evb-input"

# EVB does not have LEDs
LEDS = {}
LED_GROUPS = {}
LED_COLORS = {}
LED_DEFAULT_COLOR = ""

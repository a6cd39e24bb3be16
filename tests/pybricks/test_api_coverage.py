"""Every public name of Pybricks 2.0 for the EV3 is in our `pybricks` shim, with a compatible signature.

The list below (API) is the firmware's, as a program on an EV3 with pybricks-micropython v2.0.0 sees it:
- the Python modules of the ev3dev brick, bricks/ev3dev/modules/pybricks/*.py (hubs, ev3devices,
  nxtdevices, iodevices, parameters, tools, robotics, media/ev3dev, messaging, ev3brick, and the 1.0
  speaker.py and display.py behind ev3brick's `sound` and `display`);
- the C modules' tables, only what bricks/ev3dev/brickconfig.h compiles (PYBRICKS_HUB_EV3,
  PYBRICKS_PY_EV3DEVICES, PYBRICKS_PY_IODEVICES, PYBRICKS_PY_ROBOTICS, PYBRICKS_PY_MEDIA_EV3DEV,
  PYBRICKS_PY_PARAMETERS, PYBRICKS_PY_BUTTONS; not PYBRICKS_PY_PUPDEVICES): each MP_QSTR of a module's
  globals table and of a class's locals dict table, in extmod/modhubs.c, modev3devices.c, modmotor.c,
  modbuiltins.c (Light, ColorLight, Control), modlogger.c, modbattery.c, modbuttons.c, modrobotics.c,
  modtools.c, modiodevices.c, modnxtdevices.c, modparameters.c, modmedia_ev3dev.c and
  bricks/ev3dev/pb_type_ev3dev_image.c, pb_type_ev3dev_font.c, pb_type_ev3dev_speaker.c;
- with the parameter names and defaults of each C function's PB_PARSE_ARGS_* / mp_arg_t list, and of
  each Python def.  A C function made with MP_DEFINE_CONST_FUN_OBJ_1/2 takes its arguments by position
  only: written `(text, /)` here, the name is not checked.
The pybricks-api v2.0.0.post2 docs (doc/api/*.rst, pybricks/*.py) list a subset of these; where they
differ, the firmware is what a student's program meets, so the firmware is written here:
  GyroSensor(port, direction=...) (docs: positive_direction), Speaker.play_file(file) (docs: file_name),
  Mailbox.send(value, destination=None) (docs: brick), Motor.reset_angle(angle=None) (docs: angle),
  LogicMailbox/NumericMailbox/TextMailbox take Mailbox's encode/decode too, ColorLight.on(color,
  brightness=100) (docs: on(color)); and ABSENT lists what the docs show but the firmware lacks.

How it is checked: one simulated run (the driving base, motors on A, B, C and sensors on 1 to 4) imports
the shim, makes the objects whose instance attributes are listed (EV3Brick(), Motor(Port.A), a
DriveBase, ...) and reports each name it finds and its signature; each test below compares one module
or one class with the list.  The allow-list, api_allowlist.yaml beside this file, names what the shim
may lack or differ in, each with its reason; an entry that is no longer a difference fails too.
"""

from __future__ import annotations

import ast
import json
import re
import subprocess
from pathlib import Path

import pytest
import yaml

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.maze_file import find_maze, load_maze

HERE = Path(__file__).resolve().parent
ALLOWLIST_FILE = HERE / "api_allowlist.yaml"
FIRMWARE = Path("/work/.mirror/pybricks+pybricks-micropython/repo")  # read-only mirror, if present
FIRMWARE_TAG = "v2.0.0"

# A member is: "(signature)" a function or method (its parameters, without self); "=" a constant or
# class attribute; "." an attribute of an instance (looked at on one made in the run); "@Inner" an
# instance attribute whose value has the members of INNER["Inner"] (or of a class in API, named by its
# full path).  A class is a dict; its "__init__" is the signature of calling the class.

STOP_COAST, STOP_HOLD = "Stop.COAST", "Stop.HOLD"

INNER = {
    # extmod/modbuttons.c: buttons_globals_table (the module EV3Brick.buttons is)
    "Buttons": {"pressed": "()"},
    # extmod/modbattery.c: battery_globals_table (the module EV3Brick.battery is)
    "Battery": {"voltage": "()", "current": "()"},
    # extmod/modbuiltins.c: builtins_ColorLight_locals_dict_table, builtins_ColorLight_on
    "ColorLight": {"on": "(color, brightness=100)", "off": "()"},
    # bricks/ev3dev/pb_type_ev3dev_speaker.c: ev3dev_Speaker_locals_dict_table
    "Speaker": {
        "beep": "(frequency=500, duration=100)",
        "play_notes": "(notes, tempo=120)",
        "play_file": "(file)",
        "say": "(text)",
        "set_speech_options": "(language=None, voice=None, speed=None, pitch=None)",
        "set_volume": "(volume, which='_all_')",
    },
    # extmod/modbuiltins.c: builtins_Control_locals_dict_table (Motor.control, DriveBase.*_control)
    "Control": {
        "limits": "(speed=None, acceleration=None, actuation=None)",
        "pid": "(kp=None, ki=None, kd=None, integral_range=None, integral_rate=None, feed_forward=None)",
        "target_tolerances": "(speed=None, position=None)",
        "stall_tolerances": "(speed=None, time=None)",
        "trajectory": "()",
        "done": "()",
        "stalled": "()",
        "scale": ".",
    },
    # extmod/modlogger.c: tools_Logger_locals_dict_table (Motor.log, DriveBase.log)
    "Logger": {"start": "(duration, divisor=1)", "get": "(index=None)", "stop": "()", "save": "(path=None)"},
    # bricks/ev3dev/modules/pybricks/speaker.py: Speaker (the 1.0 ev3brick.sound)
    "Speaker1": {
        "beep": "(frequency=500, duration=100, volume=30)",
        "beeps": "(number)",
        "tune": "(frequencies_and_durations, volume=30)",
        "file": "(file_name, volume=30)",
        "speech": "(text, volume=30)",
    },
    # bricks/ev3dev/modules/pybricks/display.py: Display (the 1.0 ev3brick.display)
    "Display1": {
        "clear": "()",
        "text": "(text, location=None)",
        "image": "(file_name, location_or_alignment=Align.CENTER, clear=True)",
    },
}

SOUND_FILES = (
    "CAT_PURR DOG_BARK_1 DOG_BARK_2 DOG_GROWL DOG_SNIFF DOG_WHINE ELEPHANT_CALL INSECT_BUZZ_1 INSECT_BUZZ_2 "
    "INSECT_CHIRP SNAKE_HISS SNAKE_RATTLE T_REX_ROAR BLACK BLUE BROWN GREEN RED WHITE YELLOW BRAVO EV3 "
    "FANTASTIC GAME_OVER GO GOOD GOOD_JOB GOODBYE HELLO HI LEGO MINDSTORMS MORNING NO OKAY OKEY_DOKEY SORRY "
    "THANK_YOU YES BOING BOO CHEERING CRUNCHING CRYING FANFARE KUNG_FU LAUGHING_1 LAUGHING_2 MAGIC_WAND "
    "OUCH SHOUTING SMACK SNEEZING SNORING UH_OH ACTIVATE ANALYZE BACKWARDS COLOR DETECTED DOWN ERROR "
    "ERROR_ALARM FLASHING FORWARD LEFT OBJECT RIGHT SEARCHING START STOP TOUCH TURN UP AIR_RELEASE AIRBRAKE "
    "BACKING_ALERT HORN_1 HORN_2 LASER MOTOR_IDLE MOTOR_START MOTOR_STOP RATCHET SONAR TICK_TACK SPEED_DOWN "
    "SPEED_IDLE SPEED_UP ZERO ONE TWO THREE FOUR FIVE SIX SEVEN EIGHT NINE TEN CLICK CONFIRM GENERAL_ALERT "
    "OVERPOWER READY"
).split()
IMAGE_FILES = (
    "ANGRY AWAKE BLACK_EYE BOTTOM_LEFT BOTTOM_RIGHT CRAZY_1 CRAZY_2 DISAPPOINTED DIZZY DOWN EVIL HURT "
    "KNOCKED_OUT LOVE MIDDLE_LEFT MIDDLE_RIGHT NEUTRAL NUCLEAR PINCHED_LEFT PINCHED_MIDDLE PINCHED_RIGHT "
    "SLEEPING TEAR TIRED_LEFT TIRED_MIDDLE TIRED_RIGHT TOXIC UP WINKING ACCEPT BACKWARD DECLINE FORWARD "
    "LEFT NO_GO QUESTION_MARK RIGHT STOP_1 STOP_2 THUMBS_DOWN THUMBS_UP WARNING EV3 EV3_ICON TARGET"
).split()


def constants(names) -> dict:
    return dict.fromkeys(names if isinstance(names, list) else names.split(), "=")


IMAGE = {  # bricks/ev3dev/pb_type_ev3dev_image.c: ev3dev_Image_make_new, ev3dev_Image_locals_dict_table
    "__init__": "(source, *, sub=False, x1=None, y1=None, x2=None, y2=None)",
    "empty": "(width=178, height=128)",  # a staticmethod; 178 x 128 is the EV3's screen
    "clear": "()",
    "draw_pixel": "(x, y, color=Color.BLACK)",
    "draw_line": "(x1, y1, x2, y2, width=1, color=Color.BLACK)",
    "draw_box": "(x1, y1, x2, y2, r=0, fill=False, color=Color.BLACK)",
    "draw_circle": "(x, y, r, fill=False, color=Color.BLACK)",
    "draw_image": "(x, y, source, transparent=None)",
    "load_image": "(source, /)",
    "draw_text": "(x, y, text, text_color=Color.BLACK, background_color=None)",
    "set_font": "(font, /)",
    "print": "(*args, sep=' ', end='\\n')",
    "save": "(filename, /)",
    "width": ".",
    "height": ".",
}
MOTOR = {  # extmod/modmotor.c: motor_Motor_make_new, motor_Motor_locals_dict_table; and the 1.0
    # compatibility methods of bricks/ev3dev/modules/pybricks/ev3devices.py: Motor
    "__init__": "(port, positive_direction=Direction.CLOCKWISE, gears=None)",
    "dc": "(duty)",
    "stop": f"(stop_type={STOP_COAST})",
    "brake": "()",
    "hold": "()",
    "angle": "()",
    "speed": "()",
    "reset_angle": "(angle=None)",
    "run": "(speed)",
    "run_time": f"(speed, time, then={STOP_HOLD}, wait=True)",
    "run_until_stalled": f"(speed, then={STOP_COAST}, duty_limit=None)",
    "run_angle": f"(speed, rotation_angle, then={STOP_HOLD}, wait=True)",
    "run_target": f"(speed, target_angle, then={STOP_HOLD}, wait=True)",
    "track_target": "(target_angle)",
    "log": "@Logger",
    "control": "@Control",
    "stalled": "()",
    "set_dc_settings": "(duty_limit, duty_offset)",
    "set_run_settings": "(max_speed, acceleration)",
    "set_pid_settings": (
        "(kp, ki, kd, tight_loop_limit, angle_tolerance, speed_tolerance, stall_speed, stall_time)"
    ),
}
MAILBOX_HANDLER = {  # bricks/ev3dev/modules/pybricks/messaging.py: MailboxHandlerMixIn, under both ends
    "read_from_mailbox": "(mbox)",
    "send_to_mailbox": "(brick, mbox, payload)",
    "wait_for_mailbox_update": "(mbox)",
}
MAILBOX = {  # bricks/ev3dev/modules/pybricks/messaging.py: Mailbox
    "__init__": "(name, connection, encode=None, decode=None)",
    "read": "()",
    "send": "(value, destination=None)",
    "wait": "()",
    "wait_new": "()",
    "encode": "(value)",
    "decode": "(payload)",
    "name": ".",
}

API = {
    # extmod/modhubs.c: hubs_globals_table, hubs_EV3Brick_locals_dict_table
    "pybricks.hubs": {
        "EV3Brick": {
            "__init__": "()",
            "buttons": "@Buttons",
            "battery": "@Battery",
            "screen": "@pybricks.media.ev3dev.Image",
            "speaker": "@Speaker",
            "light": "@ColorLight",
        },
    },
    # extmod/modev3devices.c: ev3devices_globals_table and each class's table
    "pybricks.ev3devices": {
        "Motor": MOTOR,
        "TouchSensor": {"__init__": "(port)", "pressed": "()"},
        "InfraredSensor": {
            "__init__": "(port)",
            "distance": "()",
            "beacon": "(channel)",
            "buttons": "(channel)",
            "keypad": "()",
        },
        "ColorSensor": {
            "__init__": "(port)",
            "reflection": "()",
            "ambient": "()",
            "color": "()",
            "rgb": "()",
        },
        "UltrasonicSensor": {"__init__": "(port)", "distance": "(silent=False)", "presence": "()"},
        "GyroSensor": {
            "__init__": "(port, direction=Direction.CLOCKWISE)",
            "angle": "()",
            "speed": "()",
            "reset_angle": "(angle)",
        },
    },
    # extmod/modnxtdevices.c (the PYBRICKS_HUB_EV3 part) and bricks/ev3dev/modules/pybricks/nxtdevices.py
    "pybricks.nxtdevices": {
        "TouchSensor": {"__init__": "(port)", "pressed": "()"},
        "SoundSensor": {"__init__": "(port)", "intensity": "(audible_only=True)"},
        "LightSensor": {"__init__": "(port)", "ambient": "()", "reflection": "()"},
        "UltrasonicSensor": {"__init__": "(port)", "distance": "()"},
        "ColorSensor": {
            "__init__": "(port)",
            "all": "()",
            "rgb": "()",
            "ambient": "()",
            "reflection": "()",
            "color": "()",
            "light": "@ColorLight",
        },
        "TemperatureSensor": {"__init__": "(port)", "temperature": "()"},
        "EnergyMeter": {"__init__": "(port)", "input": "()", "output": "()", "storage": "()"},
        "VernierAdapter": {
            "__init__": "(port, conversion=None)",
            "conversion": "(voltage)",
            "value": "()",
            "voltage": "()",
            "resistance": "()",
            "active": "()",
            "passive": "()",
        },
    },
    # extmod/modiodevices.c: iodevices_globals_table (LUMPDevice, and the PYBRICKS_PY_EV3DEVICES part)
    "pybricks.iodevices": {
        "LUMPDevice": {"__init__": "(port)", "read": "(mode)", "write": "(mode, data)"},
        "AnalogSensor": {
            "__init__": "(port)",
            "voltage": "()",
            "resistance": "()",
            "active": "()",
            "passive": "()",
        },
        "I2CDevice": {"__init__": "(port, address)", "read": "(reg, length=1)", "write": "(reg, data=None)"},
        "UARTDevice": {
            "__init__": "(port, baudrate, timeout=None)",
            "read": "(length=1)",
            "read_all": "()",
            "write": "(data)",
            "waiting": "()",
            "clear": "()",
        },
        "DCMotor": {  # extmod/modmotor.c: motor_DCMotor_make_new, motor_DCMotor_locals_dict_table
            "__init__": "(port, positive_direction=Direction.CLOCKWISE)",
            "dc": "(duty)",
            "stop": "()",
            "brake": "()",
        },
        "Ev3devSensor": {"__init__": "(port)", "read": "(mode)", "sensor_index": ".", "port_index": "."},
    },
    # extmod/modparameters.c: parameters_globals_table and the enums' tables; Align, SoundFile and
    # ImageFile from bricks/ev3dev/modules/pybricks/parameters.py
    "pybricks.parameters": {
        "Port": constants("A B C D S1 S2 S3 S4"),
        "Direction": constants("CLOCKWISE COUNTERCLOCKWISE"),
        "Stop": constants("COAST BRAKE HOLD"),
        "Color": constants("BLACK PURPLE BLUE GREEN YELLOW ORANGE RED WHITE BROWN"),
        "Button": constants("UP DOWN LEFT RIGHT CENTER LEFT_UP LEFT_DOWN RIGHT_UP RIGHT_DOWN BEACON"),
        "Align": constants("BOTTOM_LEFT BOTTOM BOTTOM_RIGHT LEFT CENTER RIGHT TOP_LEFT TOP TOP_RIGHT"),
        "SoundFile": "=",
        "ImageFile": "=",
    },
    # extmod/modtools.c: tools_globals_table, tools_StopWatch_locals_dict_table; DataLog and print from
    # bricks/ev3dev/modules/pybricks/tools.py
    "pybricks.tools": {
        "wait": "(time)",
        "StopWatch": {"__init__": "()", "reset": "()", "time": "()", "pause": "()", "resume": "()"},
        "DataLog": {
            "__init__": "(*headers, name='log', timestamp=True, extension='csv', append=False)",
            "log": "(*values)",
        },
        "print": "=",
    },
    # extmod/modrobotics.c: robotics_DriveBase_locals_dict_table; stop and drive_time from
    # bricks/ev3dev/modules/pybricks/robotics.py: DriveBase
    "pybricks.robotics": {
        "DriveBase": {
            "__init__": "(left_motor, right_motor, wheel_diameter, axle_track)",
            "straight": "(distance)",
            "turn": "(angle)",
            "drive": "(speed, turn_rate)",
            "stop": f"(stop_type={STOP_COAST})",
            "distance": "()",
            "angle": "()",
            "state": "()",
            "reset": "()",
            "settings": "(straight_speed=None, straight_acceleration=None, turn_rate=None, turn_acceleration=None)",
            "drive_time": "(speed, steering, time)",
            "left": ".",
            "right": ".",
            "log": "@Logger",
            "heading_control": "@Control",
            "distance_control": "@Control",
        },
    },
    # extmod/modmedia_ev3dev.c and bricks/ev3dev/pb_type_ev3dev_{image,font}.c; SoundFile and ImageFile
    # from bricks/ev3dev/modules/pybricks/media/ev3dev.py
    "pybricks.media.ev3dev": {
        "SoundFile": constants(SOUND_FILES),
        "ImageFile": constants(IMAGE_FILES),
        "Font": {
            "__init__": "(family=None, size=12, bold=False, monospace=False, lang=None, script=None)",
            "DEFAULT": "=",
            "family": ".",
            "style": ".",
            "width": ".",
            "height": ".",
            "text_width": "(text, /)",
            "text_height": "(text, /)",
        },
        "Image": IMAGE,
    },
    # bricks/ev3dev/modules/pybricks/messaging.py (with bluetooth.py's RFCOMMServer under the server)
    "pybricks.messaging": {
        "Mailbox": MAILBOX,
        "LogicMailbox": MAILBOX,
        "NumericMailbox": MAILBOX,
        "TextMailbox": MAILBOX,
        "BluetoothMailboxServer": {
            "__init__": "()",
            "wait_for_connection": "(count=1)",
            "__enter__": "()",
            "__exit__": "(type, value, traceback)",
            "server_close": "()",
            "handle_request": "()",  # bluetooth.py: RFCOMMServer
            **MAILBOX_HANDLER,
        },
        "BluetoothMailboxClient": {
            "__init__": "()",
            "connect": "(brick)",
            "close": "()",
            "__enter__": "()",
            "__exit__": "(type, value, traceback)",
            **MAILBOX_HANDLER,
        },
    },
    # bricks/ev3dev/modules/pybricks/ev3brick.py: the EV3 MicroPython 1.0 module, kept by 2.0
    "pybricks.ev3brick": {
        "sound": "@Speaker1",
        "display": "@Display1",
        "battery": "@Battery",
        "light": "(color)",
        "buttons": "()",
    },
}

# What the docs (pybricks-api v2.0.0.post2) show but the firmware lacks: on an EV3 each is an
# AttributeError or ImportError, so the shim must not have it either.
ABSENT = {
    "pybricks.ev3devices.DCMotor": "pybricks/ev3devices.py of the docs; the firmware's is in iodevices",
    "pybricks.messaging.BluetoothMailboxServer.close": "the firmware's server has server_close()",
    "pybricks.hubs.EV3Brick.light.rgb": "pybricks/_common.py ColorLight.rgb of the docs; not on the EV3",
}

# The objects whose instance attributes are looked at, made in the run (the driving base robot).
INSTANCES = {
    "pybricks.hubs.EV3Brick": ("from pybricks.hubs import EV3Brick", "EV3Brick()"),
    "pybricks.ev3devices.Motor": (
        "from pybricks.ev3devices import Motor\nfrom pybricks.parameters import Port",
        "Motor(Port.A)",
    ),
    "pybricks.robotics.DriveBase": (
        "from pybricks.ev3devices import Motor\nfrom pybricks.parameters import Port\n"
        "from pybricks.robotics import DriveBase",
        "DriveBase(Motor(Port.B), Motor(Port.C), 56, 120)",
    ),
    "pybricks.iodevices.Ev3devSensor": (
        "from pybricks.iodevices import Ev3devSensor\nfrom pybricks.parameters import Port",
        "Ev3devSensor(Port.S1)",
    ),
    "pybricks.media.ev3dev.Font": ("from pybricks.media.ev3dev import Font", "Font()"),
    "pybricks.media.ev3dev.Image": ("from pybricks.media.ev3dev import Image", "Image.empty()"),
}
for _kind in ("Mailbox", "LogicMailbox", "NumericMailbox", "TextMailbox"):
    INSTANCES[f"pybricks.messaging.{_kind}"] = (
        f"from pybricks.messaging import {_kind}, BluetoothMailboxClient",
        f"{_kind}('box', BluetoothMailboxClient())",
    )


# -- the lookups the run makes, and what each must find ------------------------------------------------


def inner_members(ref: str) -> dict:
    if ref in INNER:
        return INNER[ref]
    module, _, name = ref.rpartition(".")
    return API[module][name]


def lookups() -> list[dict]:
    """[{path, root: "module:M" | "instance:M.C", chain: [...], want: "(sig)" | "=" | "." | "only"}] for every
    name; "only" (path `Class.*`) is the check that a class has no public name the firmware's has not."""
    found = []

    def add(path, root, chain, want):
        if want.startswith("@"):
            found.append({"path": path, "root": root, "chain": chain, "want": "."})
            for name, inner in inner_members(want[1:]).items():
                if name != "__init__":
                    add(f"{path}.{name}", root, [*chain, name], "." if inner == "=" else inner)
        else:
            found.append({"path": path, "root": root, "chain": chain, "want": want})

    for module, names in API.items():
        found.append({"path": module, "root": f"module:{module}", "chain": [], "want": "="})
        for name, member in names.items():
            path = f"{module}.{name}"
            if not isinstance(member, dict):
                add(path, f"module:{module}", [name], member)
                continue
            found.append({"path": path, "root": f"module:{module}", "chain": [name], "want": "="})
            found.append(
                {
                    "path": f"{path}.*",
                    "root": f"module:{module}",
                    "chain": [name],
                    "want": "only",
                    "names": sorted(member),
                }
            )
            for attr, want in member.items():
                if attr == "__init__":
                    found.append(
                        {"path": f"{path}()", "root": f"module:{module}", "chain": [name], "want": want}
                    )
                elif want.startswith(("@", ".")):
                    add(f"{path}.{attr}", f"instance:{path}", [attr], want)
                else:
                    add(f"{path}.{attr}", f"module:{module}", [name, attr], want)
    for path in ABSENT:
        module = next(m for m in API if path.startswith(m + "."))
        rest = path[len(module) + 1 :].split(".")
        cls = f"{module}.{rest[0]}"
        root = f"instance:{cls}" if len(rest) > 2 else f"module:{module}"
        chain = rest[1:] if len(rest) > 2 else rest
        found.append({"path": path, "root": root, "chain": chain, "want": "absent"})
    return found


# The program the run makes: it reports, for each lookup, what it finds there (its signature's
# parameters as [name, kind, repr of the default or null]); the comparison is done here, outside.
PROBE = """\
import inspect
import json

import pybricks  # this program runs with the Pybricks shim

LOOKUPS = json.loads({lookups!r})
INSTANCES = json.loads({instances!r})
roots = {{}}


def root(spec):
    if spec not in roots:
        kind, _, name = spec.partition(":")
        try:
            if kind == "module":
                roots[spec] = ("ok", __import__(name, fromlist=["*"]))
            elif name not in INSTANCES:
                roots[spec] = ("error", "no object of this class is made in the run to look at")
            else:
                namespace = {{}}
                exec(INSTANCES[name][0], namespace)
                roots[spec] = ("ok", eval(INSTANCES[name][1], namespace))
        except BaseException as error:
            roots[spec] = ("error", type(error).__name__ + ": " + str(error))
    return roots[spec]


def parameters(obj, holder, name):
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return None
    params = list(sig.parameters.values())
    if holder is not None and isinstance(holder, type) and inspect.isfunction(obj):
        if not isinstance(inspect.getattr_static(holder, name, None), staticmethod) and params:
            params = params[1:]  # a method looked at on its class: its self
    return [
        [p.name, p.kind.name.lower(), None if p.default is p.empty else repr(p.default)] for p in params
    ]


for lookup in LOOKUPS:
    status, obj = root(lookup["root"])
    fact = {{"path": lookup["path"]}}
    if status == "error":
        fact["error"] = obj
    else:
        holder = None
        try:
            for name in lookup["chain"]:
                holder, obj = obj, getattr(obj, name)
            fact["found"] = True
            if "names" in lookup:  # the class's public names that the firmware's has not
                fact["extra"] = sorted(n for n in dir(obj) if not n.startswith("_") and n not in lookup["names"])
            fact["callable"] = callable(obj)
            if callable(obj):
                fact["params"] = parameters(obj, holder, lookup["chain"][-1] if lookup["chain"] else "")
        except AttributeError:
            fact["found"] = False
        except BaseException as error:
            fact["error"] = type(error).__name__ + ": " + str(error)
    print("api " + json.dumps(fact))
"""


def probe_source() -> str:
    return PROBE.format(lookups=json.dumps(lookups()), instances=json.dumps(INSTANCES))


def spec_parameters(signature: str) -> list[tuple[str, str, str | None]]:
    """(name, kind, default source or None) of a signature written as "(a, b=Stop.HOLD, *, c=1)"."""
    args = ast.parse(f"def f{signature}: pass").body[0].args
    positional = [(a, "positional_only") for a in args.posonlyargs] + [
        (a, "positional_or_keyword") for a in args.args
    ]
    defaults = [None] * (len(positional) - len(args.defaults)) + [ast.unparse(d) for d in args.defaults]
    found = [(a.arg, kind, d) for (a, kind), d in zip(positional, defaults, strict=True)]
    if args.vararg:
        found.append((args.vararg.arg, "var_positional", None))
    for a, d in zip(args.kwonlyargs, args.kw_defaults, strict=True):
        found.append((a.arg, "keyword_only", None if d is None else ast.unparse(d)))
    if args.kwarg:
        found.append((args.kwarg.arg, "var_keyword", None))
    return found


def default_repr(source: str | None) -> str | None:
    """repr() of a default as the firmware's module has it: Align.CENTER is the int 5, Stop.HOLD an enum
    member (evaluated with the shim's parameters, the one module every other one builds on)."""
    if source is None:
        return None
    from pybricks import parameters

    names = {name: getattr(parameters, name) for name in ("Align", "Color", "Direction", "Stop")}
    return repr(eval(source, names))


def signature_problem(want: str, params: list | None) -> str:
    """'' when the shim's parameters take every call the firmware's take, the same way; else why not."""
    if params is None:
        return f"has no signature to compare with {want}"
    wanted = spec_parameters(want)
    shown = "(" + ", ".join(p[0] + ("" if p[2] is None else "=" + p[2]) for p in params) + ")"
    if len(params) != len(wanted):
        return f"is {shown}, the firmware's is {want}"
    for (name, kind, default), (got_name, got_kind, got_default) in zip(wanted, params, strict=True):
        if kind == "positional_only":
            ok = got_kind in ("positional_only", "positional_or_keyword")
        elif kind in ("var_positional", "var_keyword"):
            ok = got_kind == kind
        else:
            ok = got_kind == kind and got_name == name
        if not ok or got_default != default_repr(default):
            return f"is {shown}, the firmware's is {want}"
    return ""


def problem(lookup: dict, fact: dict) -> str:
    """'' when the shim has what the firmware has at this path (or lacks what it lacks); else what differs."""
    want = lookup["want"]
    if "error" in fact:
        return "absent" if want != "absent" and fact["error"].startswith("ImportError") else fact["error"]
    if want == "absent":
        return "is in the shim, but not in the firmware" if fact["found"] else ""
    if not fact["found"]:
        return "absent"
    if want == "only":
        extra = fact.get("extra", [])
        return f"has public names the firmware's has not: {', '.join(extra)}" if extra else ""
    if want.startswith("("):
        if not fact["callable"]:
            return "is not callable"
        return signature_problem(want, fact["params"])
    return ""


@pytest.fixture(scope="module")
def problems(tmp_path_factory) -> dict[str, str]:
    """{path: what differs} for every name of the list, from one run of the probe."""
    program = tmp_path_factory.mktemp("api") / "probe.py"
    program.write_text(probe_source(), encoding="utf-8")
    result = run_programs([program], load_maze(find_maze("empty")), time_limit_s=60, hang_after_s=10)
    facts = {}
    for line in (o.text for o in result.trace.output):
        if line.startswith("api "):
            fact = json.loads(line[4:])
            facts[fact["path"]] = fact
    assert facts, f"the probe printed nothing: {result.status} {result.reason}"
    found = {}
    for lookup in lookups():
        fact = facts.get(lookup["path"], {"error": f"not reached: the probe stopped ({result.reason})"})
        found[lookup["path"]] = problem(lookup, fact)
    return found


def allowlist() -> dict[str, str]:
    return yaml.safe_load(ALLOWLIST_FILE.read_text(encoding="utf-8")) or {}


def excused(path: str, allowed: dict) -> bool:
    """Whether the path, or a module or class it is in, is on the allow-list."""
    parts = re.split(r"(?=[.(])", path)
    return any("".join(parts[:i]) in allowed for i in range(1, len(parts) + 1))


def top_names() -> list[str]:
    return [module for module in API] + [
        f"{module}.{name}" for module, names in API.items() for name in names
    ]


def under(path: str, top: str) -> bool:
    return path == top or path.startswith((top + ".", top + "("))


def holder(path: str) -> str:
    """The module, class or attribute a path is a member of ('' for a module)."""
    return path[:-2] if path.endswith("()") else path.rpartition(".")[0]


def owner(path: str) -> str:
    """The module or module-level name a path belongs to (the longest that holds it)."""
    return max((top for top in top_names() if under(path, top)), key=len)


@pytest.mark.parametrize("top", top_names())
def test_the_shim_has_the_firmwares_name_with_its_signature(top, problems):
    """Each module and each of its public names, as pybricks-micropython v2.0.0 has them (the files
    named in API's comments), with the parameter names, order and defaults of the firmware."""
    allowed = allowlist()
    owned = [p for p in problems if p not in ABSENT and owner(p) == top]
    # a member of a missing module, class or attribute says nothing more than its holder
    wrong = [
        f"{p}: {problems[p]}"
        for p in owned
        if problems[p] and not excused(p, allowed) and not problems.get(holder(p))
    ]
    assert not wrong, "\n".join(wrong)


def test_what_only_the_docs_show_is_not_in_the_shim(problems):
    """ABSENT: names of the pybricks-api v2.0.0.post2 stubs that pybricks-micropython v2.0.0 has not."""
    wrong = [f"{p} ({why}): {problems[p]}" for p, why in ABSENT.items() if problems[p]]
    assert not wrong, "\n".join(wrong)


def test_every_allowed_difference_is_still_one_and_says_why(problems):
    allowed = allowlist()
    for path, reason in allowed.items():
        assert isinstance(reason, str) and len(reason.split()) >= 4, f"{path}: say why in a sentence"
        assert any(under(p, path) for p in problems), f"{path} is no name of the list"
        assert any(problems[p] for p in problems if under(p, path)), (
            f"{path} is allowed to differ, but the shim has it as the firmware does: remove it from "
            f"{ALLOWLIST_FILE.name}"
        )


def test_the_list_is_short_and_well_formed():
    for entry in lookups():
        want = entry["want"]
        if want.startswith("("):
            spec_parameters(want)  # parses
    assert len(allowlist()) <= 15, "the allow-list is meant to be short: implement instead"


# -- the list is the firmware's: each C table's names, read from the firmware's source -------------------

C_TABLES = {  # (file, table) -> the class or module of API (or INNER) that lists its names
    ("extmod/modhubs.c", "hubs_EV3Brick_locals_dict_table"): "pybricks.hubs.EV3Brick",
    ("extmod/modmotor.c", "motor_Motor_locals_dict_table"): "pybricks.ev3devices.Motor",
    ("extmod/modmotor.c", "motor_DCMotor_locals_dict_table"): "pybricks.iodevices.DCMotor",
    ("extmod/modev3devices.c", "ev3devices_globals_table"): "pybricks.ev3devices",
    ("extmod/modev3devices.c", "ev3devices_TouchSensor_locals_dict_table"): "pybricks.ev3devices.TouchSensor",
    ("extmod/modev3devices.c", "ev3devices_InfraredSensor_locals_dict_table"): (
        "pybricks.ev3devices.InfraredSensor"
    ),
    ("extmod/modev3devices.c", "ev3devices_ColorSensor_locals_dict_table"): "pybricks.ev3devices.ColorSensor",
    ("extmod/modev3devices.c", "ev3devices_UltrasonicSensor_locals_dict_table"): (
        "pybricks.ev3devices.UltrasonicSensor"
    ),
    ("extmod/modev3devices.c", "ev3devices_GyroSensor_locals_dict_table"): "pybricks.ev3devices.GyroSensor",
    ("extmod/modbuiltins.c", "builtins_ColorLight_locals_dict_table"): "ColorLight",
    ("extmod/modbuiltins.c", "builtins_Control_locals_dict_table"): "Control",
    ("extmod/modlogger.c", "tools_Logger_locals_dict_table"): "Logger",
    ("extmod/modbattery.c", "battery_globals_table"): "Battery",
    ("extmod/modbuttons.c", "buttons_globals_table"): "Buttons",
    ("extmod/modrobotics.c", "robotics_DriveBase_locals_dict_table"): "pybricks.robotics.DriveBase",
    ("extmod/modtools.c", "tools_StopWatch_locals_dict_table"): "pybricks.tools.StopWatch",
    ("extmod/modiodevices.c", "iodevices_AnalogSensor_locals_dict_table"): "pybricks.iodevices.AnalogSensor",
    ("extmod/modiodevices.c", "iodevices_I2CDevice_locals_dict_table"): "pybricks.iodevices.I2CDevice",
    ("extmod/modiodevices.c", "iodevices_UARTDevice_locals_dict_table"): "pybricks.iodevices.UARTDevice",
    ("extmod/modiodevices.c", "iodevices_Ev3devSensor_locals_dict_table"): "pybricks.iodevices.Ev3devSensor",
    ("extmod/modiodevices.c", "iodevices_LUMPDevice_locals_dict_table"): "pybricks.iodevices.LUMPDevice",
    ("extmod/modiodevices.c", "iodevices_globals_table"): "pybricks.iodevices",
    ("extmod/modnxtdevices.c", "nxtdevices_TouchSensor_locals_dict_table"): "pybricks.nxtdevices.TouchSensor",
    ("extmod/modnxtdevices.c", "nxtdevices_SoundSensor_locals_dict_table"): "pybricks.nxtdevices.SoundSensor",
    ("extmod/modnxtdevices.c", "nxtdevices_LightSensor_locals_dict_table"): "pybricks.nxtdevices.LightSensor",
    ("extmod/modnxtdevices.c", "nxtdevices_UltrasonicSensor_locals_dict_table"): (
        "pybricks.nxtdevices.UltrasonicSensor"
    ),
    ("extmod/modnxtdevices.c", "nxtdevices_ColorSensor_locals_dict_table"): "pybricks.nxtdevices.ColorSensor",
    ("extmod/modnxtdevices.c", "nxtdevices_TemperatureSensor_locals_dict_table"): (
        "pybricks.nxtdevices.TemperatureSensor"
    ),
    ("extmod/modnxtdevices.c", "nxtdevices_EnergyMeter_locals_dict_table"): "pybricks.nxtdevices.EnergyMeter",
    ("extmod/modparameters.c", "parameters_globals_table"): "pybricks.parameters",
    ("extmod/modmedia_ev3dev.c", "media_ev3dev_globals_table"): "pybricks.media.ev3dev",
    ("bricks/ev3dev/pb_type_ev3dev_image.c", "ev3dev_Image_locals_dict_table"): "pybricks.media.ev3dev.Image",
    ("bricks/ev3dev/pb_type_ev3dev_font.c", "ev3dev_Font_locals_dict_table"): "pybricks.media.ev3dev.Font",
    ("bricks/ev3dev/pb_type_ev3dev_speaker.c", "ev3dev_Speaker_locals_dict_table"): "Speaker",
}
NOT_PUBLIC = {"__name__", "__init__", "__del__"}  # a module's name, its init hook, a finaliser


def firmware_table(path: str, table: str) -> set[str]:
    """The MP_QSTR names of one table of a C file of the firmware, as the ev3dev brick compiles it (the
    names under #if PYBRICKS_HUB_NXT are not)."""
    text = subprocess.run(
        ["git", "-C", str(FIRMWARE), "show", f"{FIRMWARE_TAG}:{path}"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    body = re.search(rf"{table}\[\] = \{{(.*?)\n\}};", text, re.DOTALL).group(1)
    names, skipping = set(), []
    for line in body.splitlines():
        directive = re.match(r"\s*#\s*(if|ifdef|else|endif)\b\s*(\S*)", line)
        if directive:
            word, flag = directive.groups()
            if word in ("if", "ifdef"):
                skipping.append(flag not in ("PYBRICKS_HUB_EV3", "PYBRICKS_PY_EV3DEVICES"))
            elif word == "else":
                skipping[-1] = not skipping[-1]
            else:
                skipping.pop()
            continue
        if not any(skipping):
            names |= set(re.findall(r"MP_ROM_QSTR\(MP_QSTR_(\w+)\s*\)\s*,", line))
    return names - NOT_PUBLIC


@pytest.mark.skipif(not (FIRMWARE / "HEAD").exists(), reason="the pybricks-micropython mirror is not here")
@pytest.mark.parametrize("source, table", sorted(C_TABLES))
def test_the_list_has_every_name_of_the_firmwares_table(source, table):
    ref = C_TABLES[(source, table)]
    listed = set(API[ref]) if ref in API else set(inner_members(ref))
    assert firmware_table(source, table) == listed - {"__init__"} - python_level(ref)


def python_level(ref: str) -> set[str]:
    """Names the firmware adds in Python over a C class (bricks/ev3dev/modules/pybricks/*.py)."""
    return {
        "pybricks.ev3devices.Motor": {"stalled", "set_dc_settings", "set_run_settings", "set_pid_settings"},
        "pybricks.robotics.DriveBase": {"drive_time"},
        "pybricks.parameters": {"Align", "SoundFile", "ImageFile"},
        "pybricks.media.ev3dev": {"SoundFile", "ImageFile"},
    }.get(ref, set())

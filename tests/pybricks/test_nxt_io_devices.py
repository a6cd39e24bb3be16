"""pybricks.nxtdevices and pybricks.iodevices behave as on an EV3 with pybricks-micropython v2.0.0.

Sources (pybricks-micropython, tag v2.0.0): extmod/modnxtdevices.c (the NXT sensors for the EV3,
analog_scale), bricks/ev3dev/modules/pybricks/nxtdevices.py (VernierAdapter), extmod/modiodevices.c
(LUMPDevice, AnalogSensor, I2CDevice, UARTDevice, Ev3devSensor), bricks/ev3dev/pbdevice.c (get_values,
get_mode_switch_delay, pbdevice_set_values), lib/ev3dev/src/ev3dev_stretch/lego_sensor.c (which driver a
class accepts).  The simulator has NXT light and sound sensors and the EV3 sensors; the other devices
cannot be put on a simulated robot, so their classes find nothing, as on a brick with nothing there.
"""

from tests.inline_world import arena, robot_file

STRIPE = ["#" + "...." + "k" + "." * 13 + "#"] * 18  # one black column (x 60..72 cm) on white


def printed(result):
    assert result.status == "finished", (result.reason, result.error)
    return [line.text for line in result.trace.output]


NXT_ROBOT = (
    "{port: 1, kind: nxt-light, angle_deg: 0, radius_cm: 7, facing: down}",
    "{port: 2, kind: nxt-sound, angle_deg: 180, radius_cm: 3, facing: down}",
    "{port: 3, kind: color, angle_deg: 0, radius_cm: 7, facing: forward}",
    "{port: 4, kind: gyro, angle_deg: 180, radius_cm: 3, facing: down}",
)


def world(tmp_path, x_cm=40, inner=STRIPE, sensors=NXT_ROBOT):
    robot = robot_file(tmp_path, *sensors)
    return arena(inner=inner, start=f"x_cm: {x_cm}\n  y_cm: 120\n  heading_deg: 0", extra=f"robot: {robot}\n")


def analog_scale(mvolts, low, high, invert):
    """modnxtdevices.c analog_scale, in C's integer division (toward zero)."""
    numerator = 100 * (mvolts - low)
    scaled = int(numerator / (high - low))
    if invert:
        scaled = 100 - scaled
    return max(0, min(scaled, 100))


def test_nxt_light_sensor_scales_its_millivolts_as_the_firmware(run, tmp_path):
    """LightSensor.reflection() is analog_scale(REFLECT's millivolts, 1906, 3000, inverted) and ambient()
    analog_scale(AMBIENT's, 1906, 4164, inverted), ints 0-100 (modnxtdevices.c
    nxtdevices_LightSensor_reflection, _ambient).  The millivolts are the sensor's bin_data, read here
    through iodevices.Ev3devSensor (which returns bin_data's values, modiodevices.c Ev3devSensor_read).
    Over white paper it reads bright, over black tape dark."""
    program = """
        from pybricks.iodevices import Ev3devSensor
        from pybricks.nxtdevices import LightSensor
        from pybricks.parameters import Port
        light = LightSensor(Port.S1)
        raw = Ev3devSensor(Port.S1)
        print(raw.read("REFLECT")[0], light.reflection(), raw.read("AMBIENT")[0], light.ambient())
    """
    readings = {}
    for where, x_cm in (("white", 40 - 7), ("black", 66 - 7)):
        mv_reflect, reflection, mv_ambient, ambient = (
            int(v) for v in printed(run(program, world(tmp_path, x_cm)))[0].split()
        )
        assert reflection == analog_scale(mv_reflect, 1906, 3000, True)
        assert ambient == analog_scale(mv_ambient, 1906, 4164, True)
        readings[where] = reflection
    assert readings["white"] > 90 and readings["black"] == 0


def test_nxt_sound_sensor_hears_the_quiet_room_and_the_robots_own_speaker(run, tmp_path):
    """SoundSensor.intensity(audible_only=True) reads the active mode (mode 1, DBA) and audible_only=False
    the passive one (mode 0, DB), scaled 0-100 (modnxtdevices.c nxtdevices_SoundSensor_intensity); making
    one reads once in the active mode, which costs the sound sensor's 300 ms mode-switch delay
    (nxtdevices_SoundSensor_make_new, pbdevice.c get_mode_switch_delay).  The simulated room is quiet
    (5 %), and the robot's own speaker loud (60 %) while it beeps."""
    result = run(
        """
        import threading, time
        from pybricks.hubs import EV3Brick
        from pybricks.nxtdevices import SoundSensor
        from pybricks.parameters import Port
        start = time.time()
        sound = SoundSensor(Port.S2)
        made_in = time.time() - start
        quiet = sound.intensity()
        beeping = threading.Thread(target=lambda: EV3Brick().speaker.beep(500, 1000))
        beeping.start()
        time.sleep(0.3)
        loud = sound.intensity()
        beeping.join()
        print(made_in >= 0.3, quiet, loud, type(loud).__name__)
        """,
        world(tmp_path),
    )
    assert printed(result) == ["True 5 60 int"]


def test_ev3dev_sensor_reads_any_simulated_sensor_by_mode_name(run, tmp_path):
    """Ev3devSensor(port) takes any lego-sensor (lego_sensor.c ev3_sensor_assert_id:
    PBIO_IODEV_TYPE_ID_EV3DEV_LEGO_SENSOR); read(mode) switches to the mode named and returns its
    num_values values as a tuple of ints; a mode the sensor lacks is ValueError
    (pbdevice_get_mode_id_from_str, PBIO_ERROR_INVALID_ARG); sensor_index and port_index are the sysfs
    numbers (modiodevices.c iodevices_Ev3devSensor_make_new, _read).  LUMPDevice reads an EV3 UART sensor
    by mode number, the same values; its write() is not supported on the EV3 (pbdevice.c
    pbdevice_set_values: PBIO_ERROR_NOT_SUPPORTED, OSError EOPNOTSUPP)."""
    result = run(
        """
        from errno import EOPNOTSUPP
        from pybricks.iodevices import Ev3devSensor, LUMPDevice
        from pybricks.parameters import Port
        gyro = Ev3devSensor(Port.S4)
        print(gyro.read("GYRO-ANG"), gyro.read("GYRO-G&A"), gyro.port_index, type(gyro.sensor_index).__name__)
        light = Ev3devSensor(Port.S1)
        print(len(light.read("REFLECT")), light.read("AMBIENT")[0] > 3000)
        try:
            light.read("COL-REFLECT")
        except ValueError:
            print("ValueError")
        lump = LUMPDevice(Port.S4)
        print(lump.read(0), lump.read(3))
        try:
            lump.write(0, (1,))
        except OSError as e:
            print(e.args[0] == EOPNOTSUPP)
        """,
        world(tmp_path),
    )
    lines = printed(result)
    assert lines[0] == "(0,) (0, 0) 3 int"
    assert lines[1:] == ["1 True", "ValueError", "(0,) (0, 0)", "True"]


def test_devices_the_simulator_cannot_have_are_enodev_and_a_motor_port_is_valueerror(run, tmp_path):
    """The classes whose devices no simulated robot can carry (the NXT touch, ultrasonic, colour and
    temperature sensors, the energy meter, an analog sensor or Vernier adapter, I2C and UART devices)
    still exist with the firmware's signatures, and making one raises OSError ENODEV, as pbdevice_get_device
    does for a port without such a device; a LUMPDevice on a port whose sensor is no UART sensor is ENODEV
    too.  A motor port is ValueError (get_device: PBIO_ERROR_INVALID_PORT)."""
    result = run(
        """
        from errno import ENODEV
        from pybricks import iodevices, nxtdevices
        from pybricks.parameters import Port
        makers = [
            lambda p: nxtdevices.TouchSensor(p),
            lambda p: nxtdevices.UltrasonicSensor(p),
            lambda p: nxtdevices.ColorSensor(p),
            lambda p: nxtdevices.TemperatureSensor(p),
            lambda p: nxtdevices.EnergyMeter(p),
            lambda p: nxtdevices.VernierAdapter(p, conversion=lambda v: v * 2),
            lambda p: iodevices.AnalogSensor(p),
            lambda p: iodevices.I2CDevice(p, 0x01),
            lambda p: iodevices.UARTDevice(p, 115200, timeout=100),
            lambda p: iodevices.LUMPDevice(p),
        ]
        for make in makers:
            try:
                make(Port.S1)
            except OSError as e:
                print("ENODEV" if e.args[0] == ENODEV else e)
            try:
                make(Port.B)
            except ValueError:
                print("ValueError")
        """,
        world(tmp_path),
    )
    assert printed(result) == ["ENODEV", "ValueError"] * 10

"""LEGO ports (python-ev3dev2 2.1.0): the brick's input and output ports, and their modes."""

import sys  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)

from ev3dev2 import Device, _attribute


class LegoPort(Device):
    """
    An input or output port of the ``lego-port`` class.  Ports mostly detect
    what is plugged in; where they cannot, set ``mode`` (how the port talks
    to the device) and then ``set_device`` (the driver to load).  Find a port
    by its ``address``, e.g. ``LegoPort(INPUT_1)``.
    """

    SYSTEM_CLASS_NAME = "lego-port"
    SYSTEM_DEVICE_NAME_CONVENTION = "*"
    __slots__ = [
        "_address",
        "_driver_name",
        "_modes",
        "_mode",
        "_set_device",
        "_status",
    ]

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):

        if address is not None:
            kwargs["address"] = address
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)

        self._address = None
        self._driver_name = None
        self._modes = None
        self._mode = None
        self._set_device = None
        self._status = None

    address = _attribute("address", "The name of the port.", kind="string", writable=False)
    driver_name = _attribute(
        "driver_name", "The name of the port's driver.", kind="string", writable=False, cached=True
    )
    modes = _attribute("modes", "The modes the port supports.", kind="set", writable=False, cached=True)
    mode = _attribute(
        "mode",
        """
        The port's mode; writing a new one generally removes the devices on the
        port and loads new ones.
        """,
        kind="string",
    )
    set_device = _attribute(
        "set_device",
        "Writing a driver's name loads that device on the port (when the mode supports it).",
        kind="string",
        readable=False,
    )
    status = _attribute(
        "status",
        "Usually the same as ``mode``; in ``auto`` modes also ``no-device`` or ``error``.",
        kind="string",
        writable=False,
    )

"""The brick's power supply (python-ev3dev2 2.1.0): battery voltage and current."""

import sys  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)

from ev3dev2 import Device, _attribute


class PowerSupply(Device):
    """The ``power_supply`` class; by default the EV3's battery."""

    SYSTEM_CLASS_NAME = "power_supply"
    SYSTEM_DEVICE_NAME_CONVENTION = "*"
    __slots__ = [
        "_measured_current",
        "_measured_voltage",
        "_max_voltage",
        "_min_voltage",
        "_technology",
        "_type",
    ]

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):

        if address is not None:
            kwargs["address"] = address
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)

        self._measured_current = None
        self._measured_voltage = None
        self._max_voltage = None
        self._min_voltage = None
        self._technology = None
        self._type = None

    measured_current = _attribute(
        "current_now", "The current the battery supplies, in microamps.", writable=False
    )
    measured_voltage = _attribute("voltage_now", "The battery's voltage, in microvolts.", writable=False)
    max_voltage = _attribute(
        "voltage_max_design", "The battery's design maximum voltage, in microvolts.", writable=False
    )
    min_voltage = _attribute(
        "voltage_min_design", "The battery's design minimum voltage, in microvolts.", writable=False
    )
    technology = _attribute(
        "technology", "The battery's technology, e.g. ``Li-ion``.", kind="string", writable=False
    )
    type = _attribute("type", "The supply's type, e.g. ``Battery``.", kind="string", writable=False)

    @property
    def measured_amps(self):
        """The current the battery supplies, in amps."""
        return self.measured_current / 1e6

    @property
    def measured_volts(self):
        """The battery's voltage, in volts."""
        return self.measured_voltage / 1e6

"""Where a robot stands: position of its centre (midway between the wheels) and heading."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Pose:
    """x, y in cm from the bottom-left corner; heading in degrees, 0 = +x, counter-clockwise positive."""

    x_cm: float
    y_cm: float
    heading_deg: float = 0.0

    def as_dict(self) -> dict[str, float]:
        """Plain values for traces and JSON."""
        return {"x_cm": self.x_cm, "y_cm": self.y_cm, "heading_deg": self.heading_deg}

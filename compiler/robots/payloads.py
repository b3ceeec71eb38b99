"""Rated payloads (kg) of the library arms this branch's tests and examples need (issue #14).

`Robot.rated_payload_kg` (None = unknown: the payload is not checked). The robot-data issue
(#12) gives every library arm its rated payload under the same attribute name; these are the
same numbers, each from the vendor's datasheet:
  * ur10e        12.5 kg — Universal Robots, "UR10e Technical specifications" datasheet
                 (Specification: Payload 12.5 kg);
  * ur5e          5.0 kg — Universal Robots, "UR5e Technical specifications" datasheet
                 (Specification: Payload 5 kg);
  * abb_irb1600   6.0 kg — ABB, "Product specification IRB 1600/1660", variant
                 IRB 1600-6/1.45: handling capacity 6 kg (the "-6" of the model name).
"""

from __future__ import annotations

__all__ = ["RATED_PAYLOAD_KG"]

RATED_PAYLOAD_KG: dict[str, float] = {"ur10e": 12.5, "ur5e": 5.0, "abb_irb1600": 6.0}

#!/usr/bin/env python3
"""spot_lights.py IN.gltf OUT.gltf [--inner A] [--outer B]: the same file with every KHR_lights_punctual
point light turned into a spot light of the same colour, intensity, range and position, pointing
straight down (-Y; inner cone A, outer cone B radians, defaults 0.5 and 0.9). Buffers and images keep
their URIs, so OUT must sit beside IN. Used by scripts/device-run.sh spot-cost to compare spot and
point lights of the same count and range."""
import argparse
import json
import math

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("src")
ap.add_argument("dst")
ap.add_argument("--inner", type=float, default=0.5)
ap.add_argument("--outer", type=float, default=0.9)
a = ap.parse_args()
if not 0 <= a.inner < a.outer <= math.pi / 2:
    ap.error("need 0 <= inner < outer <= pi/2")
with open(a.src) as f:
    d = json.load(f)
lights = d.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
spots = 0
for light in lights:
    if light.get("type") == "point":
        light["type"] = "spot"
        light["spot"] = {"innerConeAngle": a.inner, "outerConeAngle": a.outer}
        spots += 1
down = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -90 degrees about X: local -Z to world -Y
for node in d.get("nodes", []):
    if "KHR_lights_punctual" in node.get("extensions", {}):
        node["rotation"] = down
with open(a.dst, "w") as f:
    json.dump(d, f)
print("%s: %d spot lights" % (a.dst, spots))

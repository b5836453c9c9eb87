"""Writes expected.json: the Yeadon model of every rider file here, as computed by the Python
package `yeadon` (PyPI), for whipple's cross-check (crates/whipple/tests/yeadon.rs).

Run with a throw-away venv that has `yeadon` installed:

    python3 -m venv /tmp/yeadon-venv && /tmp/yeadon-venv/bin/pip install yeadon
    cd crates/whipple/tests/data/yeadon && /tmp/yeadon-venv/bin/python expected.py > expected.json

The Python package's tests import `cases()` and compare it with `whipple rider-inertia`
(crates/whipple-py/tests/test_yeadon.py).

yeadon 2.0.1 is corrected in three places before it runs (each is checked independently in
whipple's own tests, so the cross-check is not circular):
1. a stadium solid whose two ends are circles (a truncated cone) has its mass centre measured
   from the wrong end (yeadon swaps the ends for t0 = 0 and swaps back only when the new t0 is
   not zero); the correction moves it to h - z;
2. a segment's and a solid's inertia in the global frame is R^T I R where R maps local
   components to global ones (the inverse rotation); the correction uses R I R^T;
3. a stadium solid's moment about its x axis (across the stadium's long direction) has the
   cross-section term 4 r t^3 / 3 F4(a, b) where the integral of y^2 over the stadium gives
   4 r^3 t / 3 F4(b, a) (the perpendicular-axis theorem fails for yeadon's value); the
   correction adds the difference.
yeadon's uncorrected whole-body mass centre and inertia are kept too (`yeadon_as_published`).
A Human is also built from the measurements before the configuration is applied with
set_CFG_dict, since Human(meas, cfg_path) reads the file without updating the segments.
"""
import copy
import glob
import json
import os
import sys
import warnings

import numpy as np
import yaml
import yeadon
from yeadon import inertia, solid, segment

ORIGINAL_DENSITIES = copy.deepcopy(yeadon.Human.segmental_densities)
ORIGINAL_STADIUM_SOLID = solid.StadiumSolid.calc_rel_properties


def corrected_stadium_solid(self):
    ORIGINAL_STADIUM_SOLID(self)
    first, second = (self.stads[1], self.stads[0]) if self.degenerate_by_t0 else self.stads
    r0, t0, r1, t1 = first.radius, first.thickness, second.radius, second.thickness
    a = (r1 - r0) / r0
    b = 1.0 if t0 == 0 else (t1 - t0) / t0
    delta = self.density * self.height * 4.0 / 3.0 * (
        r0**3 * t0 * self._F4(b, a) - r0 * t0**3 * self._F4(a, b))
    axis = 1 if self.alignment == 'AP' else 0
    self._rel_inertia[axis, axis] += delta
    if self.degenerate_by_t0 and self.stads[1].thickness == 0:
        self._rel_center_of_mass = np.array([[0.0], [0.0], [self.height - self._rel_center_of_mass[2, 0]]])


def corrected_solid_properties(self):
    self._center_of_mass = self.pos + self._rot_mat @ self.rel_center_of_mass
    self._inertia = self._rot_mat @ self.rel_inertia @ self._rot_mat.T


def corrected_segment_properties(self):
    self._center_of_mass = self.pos + self.rot_mat @ self.rel_center_of_mass
    self._inertia = self.rot_mat @ self.rel_inertia @ self.rot_mat.T


ORIGINAL = (solid.StadiumSolid.calc_rel_properties, solid.Solid.calc_properties,
            segment.Segment.calc_properties)
CORRECTED = (corrected_stadium_solid, corrected_solid_properties, corrected_segment_properties)


def patch(functions):
    (solid.StadiumSolid.calc_rel_properties, solid.Solid.calc_properties,
     segment.Segment.calc_properties) = functions


def human(meas, cfg):
    # yeadon scales its class-level densities in place by a file's totalmass: start afresh.
    yeadon.Human.segmental_densities = copy.deepcopy(ORIGINAL_DENSITIES)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter('always')
        h = yeadon.Human(meas)
        if cfg is not None:
            h.set_CFG_dict({k: float(v) for k, v in read_yaml(cfg).items()})
    return h, [str(w.message) for w in caught]


def read_yaml(path):
    with open(path) as f:
        return yaml.safe_load(f)


def flat(a):
    return [float(x) for x in np.asarray(a).ravel()]


HERE = os.path.dirname(os.path.abspath(__file__))


def cases():
    """Every measurement file here in the zero configuration and in each of its configuration
    files (Jason also in ArbitraryYeadonCFG.txt), as yeadon computes them (corrected)."""
    out = []
    for meas_path in sorted(glob.glob(os.path.join(HERE, '*YeadonMeas.txt'))):
        meas = os.path.basename(meas_path)
        rider = meas[:-len('YeadonMeas.txt')]
        cfgs = [None] + sorted(os.path.basename(p) for p in
                               glob.glob(os.path.join(HERE, rider + '*YeadonCFG.txt')))
        if rider == 'Jason':
            cfgs.append('ArbitraryYeadonCFG.txt')
        for cfg in cfgs:
            cfg_path = None if cfg is None else os.path.join(HERE, cfg)
            try:
                patch(ORIGINAL)
                raw, _ = human(meas_path, cfg_path)
                patch(CORRECTED)
                h, caught = human(meas_path, cfg_path)
            finally:
                patch(ORIGINAL)
            out.append({
                'measurements': meas,
                'configuration': cfg,
                'warnings': caught,
                'mass': float(h.mass),
                'center_of_mass': flat(h.center_of_mass),
                'inertia': flat(h.inertia),
                'segments': [{
                    'name': s.label.split(':')[0],
                    'mass': float(s.mass),
                    'center_of_mass': flat(s.center_of_mass),
                    'orientation': flat(s.rot_mat),
                    'local_inertia': flat(s.rel_inertia),
                    'inertia': flat(s.inertia),
                } for s in h.segments],
                'yeadon_as_published': {
                    'center_of_mass': flat(raw.center_of_mass),
                    'inertia': flat(raw.inertia),
                },
            })
    yeadon.Human.segmental_densities = copy.deepcopy(ORIGINAL_DENSITIES)
    return out


if __name__ == '__main__':
    json.dump({'yeadon': yeadon.__version__, 'cases': cases()}, sys.stdout, indent=1)
    sys.stdout.write('\n')

# Licensed under a 3-clause BSD style license - see licenses/LICENSE.rst
"""Run by tests/visibilities/test_casa.py in a subprocess, with CASA configured offline there.

``python casa_sim.py simulate vla|alma OUT.ms``: CASA's simulator
(casatools.simulator) observes a polarized point source (I = 1 Jy, Q = 0.06,
U = 0.08) for 8 hours with four antennas of the VLA (circular feeds) or ALMA
(linear feeds), and predicts the data from a component list.

``python casa_sim.py simulate vla2 OUT.ms``: the VLA set with two spectral
windows (5 and 8 GHz), observed one after the other in each scan: the same
times in two scans (pyuvdata refuses such sets).

``python casa_sim.py split MS OUT``: CASA's ``split(datacolumn="corrected")``:
CORRECTED_DATA into the DATA of a new set.

``python casa_sim.py check``: CASA starts (imports) here.

``python casa_sim.py applycal MS``: CASA's ``applycal(parang=True)``, no
calibration table: DATA with the parallactic angle removed into
CORRECTED_DATA.

``python casa_sim.py importfitsidi FITS MS``: CASA's ``importfitsidi``, a
FITS-IDI file into a new Measurement Set.
"""

import importlib
import sys

import numpy as np


def simulate(kind, out):
    import casatools

    me, sm, cl = casatools.measures(), casatools.simulator(), casatools.componentlist()
    if kind in ("vla", "vla2"):
        observatory, stokes, feed = "VLA", "RR RL LR LL", "perfect R L"
        # Pads near the VLA centre (ITRF, m).
        xyz = np.array([[-1601185.4, -5041977.5, 3554875.9],
                        [-1601614.1, -5042001.7, 3554652.5],
                        [-1601145.9, -5041659.6, 3555386.3],
                        [-1602044.9, -5042025.8, 3554427.8]])
        source = ("J2000", "13h31m08.288s", "30d30m32.96s")  # 3C 286
    else:
        observatory, stokes, feed = "ALMA", "XX XY YX YY", "perfect X Y"
        xyz = np.array([[2225061.8, -5440057.4, -2481681.1],
                        [2225142.4, -5440021.9, -2481671.7],
                        [2225035.4, -5440108.8, -2481623.3],
                        [2225101.9, -5440063.6, -2481650.0]])
        source = ("J2000", "12h29m06.7s", "02d03m08.6s")  # 3C 273
    sm.open(out)
    sm.setconfig(telescopename=observatory, x=xyz[:, 0], y=xyz[:, 1], z=xyz[:, 2],
                 dishdiameter=[12.0] * 4, mount=["alt-az"] * 4,
                 antname=[f"A{k}" for k in range(4)], coordsystem="global",
                 referencelocation=me.observatory(observatory))
    sm.setspwindow(spwname="spw0", freq="5GHz", deltafreq="1MHz", freqresolution="1MHz",
                   nchannels=2, stokes=stokes)
    if kind == "vla2":
        sm.setspwindow(spwname="spw1", freq="8GHz", deltafreq="2MHz", freqresolution="2MHz",
                       nchannels=3, stokes=stokes)
    sm.setfeed(mode=feed)
    sm.setfield(sourcename="src", sourcedirection=me.direction(*source))
    sm.setlimits(shadowlimit=0.001, elevationlimit="8deg")
    sm.setauto(autocorrwt=0.0)
    sm.settimes(integrationtime="600s", usehourangle=True,
                referencetime=me.epoch("utc", "2023/01/25/00:00:00"))
    sm.observe("src", "spw0", starttime="-5h", stoptime="5h")
    if kind == "vla2":
        sm.observe("src", "spw1", starttime="-5h", stoptime="5h")
    cl.addcomponent(flux=[1.0, 0.06, 0.08, 0.0], fluxunit="Jy", polarization="Stokes",
                    dir=me.direction(*source), shape="point", freq="5GHz")
    cl.rename(out + ".cl")
    cl.close()
    sm.predict(complist=out + ".cl")
    sm.close()


def importfitsidi(fits, ms):
    from casatasks import importfitsidi as task

    task(fitsidifile=[fits], vis=ms)


def applycal(ms):
    from casatasks import applycal as task

    task(vis=ms, parang=True)


def split(ms, out):
    from casatasks import split as task

    task(vis=ms, outputvis=out, datacolumn="corrected")


if __name__ == "__main__":
    if sys.argv[1] == "check":
        for name in ("casatools", "casatasks"):
            importlib.import_module(name)
    elif sys.argv[1] == "simulate":
        simulate(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "importfitsidi":
        importfitsidi(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "split":
        split(sys.argv[2], sys.argv[3])
    else:
        applycal(sys.argv[2])
    print("done")

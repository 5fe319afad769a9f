# `import stiffpath` stays cheap: it loads neither NumPy (imported when the first array is made) nor OpenCV.
import subprocess
import sys


def test_import_loads_neither_numpy_nor_opencv():
    check = ("import sys, stiffpath\n"
             "assert 'numpy' not in sys.modules, 'numpy imported'\n"
             "maps = open('/proc/self/maps').read()\n"
             "assert 'libopencv' not in maps, 'OpenCV loaded'\n"
             "r = stiffpath.Robot('oc-gu')\n"
             "assert r.ik([0.222132, 0.0375]).shape == (2,) and 'numpy' in sys.modules\n"
             "assert stiffpath.joints_dtype.names[-1] == 'line'\n")
    subprocess.run([sys.executable, "-c", check], check=True)

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


def test_vision_loads_opencv_on_first_use_only():
    check = ("import os, sys, stiffpath\n"
             "loaded = lambda: 'libopencv' in open('/proc/self/maps').read()\n"
             "assert not loaded()\n"
             "try:\n"
             "    vision = stiffpath.vision\n"
             "except AttributeError as e:\n"
             "    assert os.environ.get('STIFFPATH_PYTHON_VISION') != '1', e\n"
             "    assert 'no vision part' in str(e)\n"
             "    sys.exit(0)\n"
             "assert loaded() and vision.Error is stiffpath.Error\n"
             "import stiffpath.vision\n"
             "from stiffpath import vision as again\n"
             "assert stiffpath.vision is vision is again is sys.modules['stiffpath.vision']\n"
             "assert type(vision.render_scan(length_m=0.002).truth) is stiffpath.PathMetrics\n")
    subprocess.run([sys.executable, "-c", check], check=True)

import sys, numpy as np
import roughcontact.gap_solver as gs
from roughcontact.scene import load_scene
from roughcontact import study
scene = load_scene(preset='draft')
for a in [float(x) for x in sys.argv[1:]]:
    gs.APPROACH = a
    res = study.run_study(scene, workers=1)
    for row in res.points:
      for p in row:
        print(a, p.normal_force, p.voltage, f'{np.mean(p.equivalent_gap):.4e}', f'{np.mean(p.contact_fraction):.4f}', sum(p.iterations))

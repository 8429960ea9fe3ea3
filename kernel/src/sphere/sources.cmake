# sphere: ray–sphere (docs/contract.md §10) goes here: its formula, stages, cascade, exact stage and entry
# points, on core's stages and the one escalation policy, registered with the nearest-hit module and the BVH.

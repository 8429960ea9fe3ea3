# box: the ray–box slab test of the BVH walk (ray_box.hpp, header only).

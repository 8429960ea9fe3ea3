# orient: the orient2d/orient3d filters of inside() (orient_predicates.hpp, header only).

// Fixture for the layering check: a pure library that includes GL must fail it.
#include <GLES3/gl3.h>

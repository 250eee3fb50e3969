// evas.Problem: the library problems from Python (problem_binding.cpp).
#pragma once

#include <pybind11/pybind11.h>

void bind_problems(pybind11::module_& m);

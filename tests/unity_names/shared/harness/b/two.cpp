// A fixture of scripts/check_unity_names.py: `twice` is private to this source and to a/one.cpp;
// in one unity batch a call twice(1) here could bind to a/one.cpp's int overload.
namespace {

double twice(double x) {
  return 2.0 * x;
}

}  // namespace

double two() {
  return twice(1.0);
}

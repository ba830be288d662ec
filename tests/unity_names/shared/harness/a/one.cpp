// A fixture of scripts/check_unity_names.py: `twice` is private to this source and to b/two.cpp.
namespace {

int twice(int x) {
  return 2 * x;
}

}  // namespace

int one() {
  return twice(1);
}

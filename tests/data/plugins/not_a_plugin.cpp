// A shared library without sdgbehave's entry points.
extern "C" int some_other_function(void) { return 1; }

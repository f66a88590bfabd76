// diff tests

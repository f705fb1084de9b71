// dtlab: the headless command line of Delaunay Lab.
int main() { return 0; }

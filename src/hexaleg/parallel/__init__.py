"""Work spread over processes that end with their parent: forked maps sharing the robot,
pool workers that die with their parent, the output directory's lock, Ctrl-C and SIGTERM as an
exception that stops them."""

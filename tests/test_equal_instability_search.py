"""The equal-instability bisection (:mod:`stability.study.equal_instability`) against closed-form time-vs-speed laws."""

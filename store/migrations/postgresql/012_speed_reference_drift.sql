-- Which speed the vehicle's loop holds (over ground or through the water) and how fast a
-- straight-line prediction's error grows, from the mission's steady legs
-- (kinematics/speed_reference.hpp, kinematics/drift_scatter.hpp), kept with the current they
-- were judged in. NULL where not evaluated (every estimate stored before); reference_legs set
-- with speed_reference NULL: evaluated and undetermined.
ALTER TABLE mission_currents ADD COLUMN reference_legs BIGINT;
ALTER TABLE mission_currents ADD COLUMN rms_over_ground_mps DOUBLE PRECISION;
ALTER TABLE mission_currents ADD COLUMN rms_through_water_mps DOUBLE PRECISION;
ALTER TABLE mission_currents ADD COLUMN reference_separation_mps DOUBLE PRECISION;
ALTER TABLE mission_currents ADD COLUMN speed_reference TEXT
  CHECK (speed_reference IN ('over_ground', 'through_water'));
ALTER TABLE mission_currents ADD COLUMN drift_legs BIGINT;
ALTER TABLE mission_currents ADD COLUMN drift_along_mps DOUBLE PRECISION;
ALTER TABLE mission_currents ADD COLUMN drift_cross_mps DOUBLE PRECISION;
ALTER TABLE mission_currents ADD COLUMN drift_mean_leg_s DOUBLE PRECISION;

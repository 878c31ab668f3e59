-- The speed commanded with the new heading when a turn changes speed (u1;
-- commanded_speed_mps stays u0). NULL for a constant-speed turn and every older turn.
ALTER TABLE turns ADD COLUMN speed_after_mps DOUBLE PRECISION;

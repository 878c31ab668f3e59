// Example mission files, embedded because the server serves web/ only (not examples/).
// Copies of examples/thesis-fig4-1.json and examples/persistent-excitation.json; the e2e test
// checks that they still equal the originals.

export const EXAMPLES = {
  'thesis-fig4-1': {
    "name": "thesis-fig4-1",
    "kind": "turns",
    "turn_array": {
      "speeds_mps": [
        0.5,
        1.0,
        1.5
      ],
      "dheadings_deg": [
        10,
        40,
        70,
        100,
        130,
        160
      ],
      "direction": "alternate",
      "repeats": 1
    },
    "condition_set": {
      "speed_tolerance_mps": 0.1,
      "max_yaw_rate_dps": 1.0,
      "window": 5
    },
    "constant_heading": {
      "completion_threshold_deg": 5
    },
    "operating_region": {
      "polygon_m": [
        [
          -100,
          -100
        ],
        [
          100,
          -100
        ],
        [
          100,
          100
        ],
        [
          -100,
          100
        ]
      ],
      "buffer_m": 25,
      "return_point_m": [
        0,
        -70
      ]
    }
  },
  'persistent-excitation': {
    "name": "persistent-excitation",
    "kind": "persistent_excitation",
    "excitation": {
      "speed_mps": 1.0,
      "duration_s": 900,
      "min_step_deg": 20,
      "max_step_deg": 120,
      "min_interval_s": 3,
      "max_interval_s": 10,
      "seed": 7
    },
    "operating_region": {
      "polygon_m": [
        [
          -80,
          -80
        ],
        [
          80,
          -80
        ],
        [
          80,
          80
        ],
        [
          -80,
          80
        ]
      ],
      "buffer_m": 12,
      "return_point_m": [
        0,
        -60
      ]
    }
  },
};

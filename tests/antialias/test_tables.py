"""Look-up tables of Wang 1989 §4.7/§4.8: Tables 4-1..4-9, 5-1, 5-3, 5-4, Fig 5-2, the LUT's error."""

import math
from fractions import Fraction

import numpy as np
import pytest
from numba import njit

from scanviz.antialias import columns
from scanviz.antialias.tables import (
    DIVISIONS,
    PRINTED_PERIODS,
    column_indices,
    degree_slope,
    distance_index,
    edge_tables,
    intensities,
    line_table,
    period_rule,
    periodic_table,
    printed_period,
    slope_index,
)

# Table 4-1 (spec §3.7): dxy, (up, mid, low), 16 levels (up, mid, low), 256 levels (up, mid, low).
TABLE_4_1 = [
    (0.0000, 0.0119, 0.9800, 0.0119, 0, 15, 0, 3, 250, 3),
    (0.0875, 0.0894, 0.9144, 0.0000, 1, 14, 0, 23, 233, 0),
    (0.1750, 0.1769, 0.8269, 0.0000, 3, 12, 0, 45, 211, 0),
    (0.2625, 0.2644, 0.7394, 0.0000, 4, 11, 0, 67, 189, 0),
    (0.3500, 0.3519, 0.6520, 0.0000, 5, 10, 0, 90, 166, 0),
    (0.4374, 0.4393, 0.5645, 0.0000, 7, 8, 0, 112, 144, 0),
    (-0.4751, 0.0000, 0.5268, 0.4770, 0, 8, 7, 0, 134, 122),
    (-0.3876, 0.0000, 0.6143, 0.3895, 0, 9, 6, 0, 157, 99),
    (-0.3001, 0.0000, 0.7018, 0.3020, 0, 11, 5, 0, 179, 77),
    (-0.2126, 0.0000, 0.7893, 0.2145, 0, 12, 3, 0, 201, 55),
    (-0.1251, 0.0000, 0.8768, 0.1270, 0, 13, 2, 0, 224, 32),
    (-0.0376, 0.0004, 0.9638, 0.0396, 0, 14, 1, 0, 246, 10),
    (0.0499, 0.0518, 0.9521, 0.0000, 1, 14, 0, 13, 243, 0),
    (0.1373, 0.1393, 0.8646, 0.0000, 2, 13, 0, 36, 220, 0),
    (0.2248, 0.2267, 0.7771, 0.0000, 3, 12, 0, 58, 198, 0),
    (0.3123, 0.3142, 0.6896, 0.0000, 5, 10, 0, 80, 176, 0),
    (0.3998, 0.4017, 0.6021, 0.0000, 6, 9, 0, 102, 154, 0),
    (0.4873, 0.4892, 0.5146, 0.0000, 7, 8, 0, 125, 131, 0),
    (-0.4252, 0.0000, 0.5767, 0.4271, 0, 9, 6, 0, 147, 109),
    (-0.3377, 0.0000, 0.6642, 0.3396, 0, 10, 5, 0, 169, 87),
    (-0.2502, 0.0000, 0.7517, 0.2522, 0, 11, 4, 0, 192, 64),
    (-0.1628, 0.0000, 0.8392, 0.1647, 0, 13, 2, 0, 214, 42),
    (-0.0753, 0.0000, 0.9266, 0.0772, 0, 14, 1, 0, 236, 20),
    (0.0122, 0.0191, 0.9783, 0.0064, 0, 15, 0, 5, 249, 2),
    (0.0997, 0.1016, 0.9022, 0.0000, 2, 14, 0, 26, 230, 0),
    (0.1872, 0.1891, 0.8147, 0.0000, 3, 12, 0, 48, 208, 0),
    (0.2747, 0.2766, 0.7272, 0.0000, 4, 11, 0, 71, 185, 0),
    (0.3622, 0.3641, 0.6397, 0.0000, 5, 10, 0, 93, 163, 0),
    (0.4497, 0.4516, 0.5523, 0.0000, 7, 8, 0, 115, 141, 0),
    (-0.4629, 0.0000, 0.5391, 0.4648, 0, 8, 7, 0, 137, 119),
    (-0.3754, 0.0000, 0.6265, 0.3773, 0, 9, 6, 0, 160, 96),
    (-0.2879, 0.0000, 0.7140, 0.2898, 0, 11, 4, 0, 182, 74),
    (-0.2004, 0.0000, 0.8015, 0.2023, 0, 12, 3, 0, 204, 52),
    (-0.1129, 0.0000, 0.8890, 0.1148, 0, 13, 2, 0, 227, 29),
    (-0.0254, 0.0023, 0.9726, 0.0289, 0, 15, 0, 1, 248, 7),
    (0.0621, 0.0640, 0.9398, 0.0000, 1, 14, 0, 16, 240, 0),
    (0.1496, 0.1515, 0.8524, 0.0000, 2, 13, 0, 39, 217, 0),
    (0.2370, 0.2390, 0.7649, 0.0000, 4, 11, 0, 61, 195, 0),
    (0.3245, 0.3264, 0.6774, 0.0000, 5, 10, 0, 83, 173, 0),
    (0.4120, 0.4139, 0.5899, 0.0000, 6, 9, 0, 106, 150, 0),
    (0.4995, 0.5014, 0.5024, 0.0000, 8, 8, 0, 128, 128, 0),
    (-0.4130, 0.0000, 0.5889, 0.4149, 0, 9, 6, 0, 150, 106),
    (-0.3255, 0.0000, 0.6764, 0.3274, 0, 10, 5, 0, 172, 83),
    (-0.2380, 0.0000, 0.7639, 0.2399, 0, 11, 4, 0, 195, 61),
    (-0.1505, 0.0000, 0.8514, 0.1524, 0, 13, 2, 0, 217, 39),
    (-0.0631, 0.0000, 0.9389, 0.0650, 0, 14, 1, 0, 239, 17),
    (0.0244, 0.0281, 0.9732, 0.0026, 0, 15, 0, 7, 248, 1),
    (0.1119, 0.1138, 0.8900, 0.0000, 2, 13, 0, 29, 227, 0),
    (0.1994, 0.2013, 0.8025, 0.0000, 3, 12, 0, 51, 205, 0),
    (0.2869, 0.2888, 0.7150, 0.0000, 4, 11, 0, 74, 182, 0),
    (0.3744, 0.3763, 0.6275, 0.0000, 6, 9, 0, 96, 160, 0),
    (0.4619, 0.4638, 0.5400, 0.0000, 7, 8, 0, 118, 138, 0),
    (-0.4506, 0.0000, 0.5513, 0.4525, 0, 8, 7, 0, 141, 115),
    (-0.3631, 0.0000, 0.6388, 0.3651, 0, 10, 5, 0, 163, 93),
    (-0.2757, 0.0000, 0.7262, 0.2776, 0, 11, 4, 0, 185, 71),
    (-0.1882, 0.0000, 0.8137, 0.1901, 0, 12, 3, 0, 208, 48),
    (-0.1007, 0.0000, 0.9012, 0.1026, 0, 14, 2, 0, 230, 26),
    (-0.0132, 0.0060, 0.9780, 0.0198, 0, 15, 0, 2, 249, 5),
    (0.0743, 0.0762, 0.9276, 0.0000, 1, 14, 0, 19, 237, 0),
    (0.1618, 0.1637, 0.8401, 0.0000, 2, 13, 0, 42, 214, 0),
    (0.2493, 0.2512, 0.7526, 0.0000, 4, 11, 0, 64, 192, 0),
    (0.3368, 0.3387, 0.6652, 0.0000, 5, 10, 0, 86, 170, 0),
    (0.4242, 0.4262, 0.5777, 0.0000, 6, 9, 0, 109, 147, 0),
    (-0.4883, 0.0000, 0.5136, 0.4902, 0, 8, 7, 0, 131, 125),
    (-0.4008, 0.0000, 0.6011, 0.4027, 0, 9, 6, 0, 153, 103),
    (-0.3133, 0.0000, 0.6886, 0.3152, 0, 10, 5, 0, 176, 80),
    (-0.2258, 0.0000, 0.7761, 0.2277, 0, 12, 3, 0, 198, 58),
    (-0.1383, 0.0000, 0.8636, 0.1402, 0, 13, 2, 0, 220, 36),
    (-0.0508, 0.0000, 0.9511, 0.0527, 0, 14, 1, 0, 243, 13),
    (0.0367, 0.0387, 0.9646, 0.0005, 1, 14, 0, 10, 246, 0),
    (0.1241, 0.1261, 0.8778, 0.0000, 2, 13, 0, 32, 224, 0),
    (0.2116, 0.2135, 0.7903, 0.0000, 3, 12, 0, 54, 202, 0),
    (0.2991, 0.3010, 0.7028, 0.0000, 5, 11, 0, 77, 179, 0),
    (0.3866, 0.3885, 0.6153, 0.0000, 6, 9, 0, 99, 157, 0),
    (0.4741, 0.4760, 0.5278, 0.0000, 7, 8, 0, 121, 135, 0),
    (-0.4384, 0.0000, 0.5635, 0.4403, 0, 8, 7, 0, 144, 112),
    (-0.3509, 0.0000, 0.6510, 0.3528, 0, 10, 5, 0, 166, 90),
    (-0.2634, 0.0000, 0.7385, 0.2654, 0, 11, 4, 0, 188, 68),
    (-0.1760, 0.0000, 0.8260, 0.1779, 0, 12, 3, 0, 211, 45),
    (-0.0885, 0.0000, 0.9134, 0.0904, 0, 14, 1, 0, 233, 23),
    (-0.0010, 0.0114, 0.9800, 0.0124, 0, 15, 0, 3, 250, 3),
    (0.0865, 0.0884, 0.9154, 0.0000, 1, 14, 0, 23, 233, 0),
    (0.1740, 0.1759, 0.8279, 0.0000, 3, 12, 0, 45, 211, 0),
    (0.2615, 0.2634, 0.7404, 0.0000, 4, 11, 0, 67, 189, 0),
    (0.3490, 0.3509, 0.6529, 0.0000, 5, 10, 0, 89, 166, 0),
    (0.4365, 0.4384, 0.5655, 0.0000, 7, 8, 0, 112, 144, 0),
    (-0.4761, 0.0000, 0.5259, 0.4780, 0, 8, 7, 0, 134, 122),
    (-0.3886, 0.0000, 0.6133, 0.3905, 0, 9, 6, 0, 156, 100),
    (-0.3011, 0.0000, 0.7008, 0.3030, 0, 11, 5, 0, 179, 77),
    (-0.2136, 0.0000, 0.7883, 0.2155, 0, 12, 3, 0, 201, 55),
    (-0.1261, 0.0000, 0.8758, 0.1280, 0, 13, 2, 0, 223, 33),
    (-0.0386, 0.0003, 0.9630, 0.0406, 0, 14, 1, 0, 246, 10),
    (0.0489, 0.0508, 0.9530, 0.0000, 1, 14, 0, 13, 243, 0),
    (0.1364, 0.1383, 0.8655, 0.0000, 2, 13, 0, 35, 221, 0),
    (0.2238, 0.2258, 0.7781, 0.0000, 3, 12, 0, 58, 198, 0),
    (0.3113, 0.3132, 0.6906, 0.0000, 5, 10, 0, 80, 176, 0),
    (0.3988, 0.4007, 0.6031, 0.0000, 6, 9, 0, 102, 154, 0),
    (0.4863, 0.4882, 0.5156, 0.0000, 7, 8, 0, 124, 131, 0),
    (-0.4262, 0.0000, 0.5757, 0.4281, 0, 9, 6, 0, 147, 109),
    (-0.3387, 0.0000, 0.6632, 0.3406, 0, 10, 5, 0, 169, 87),
]  # fmt: skip
# Tables 4-2, 4-4, 4-3: degree -> (p, m·p, n, precision in area, in intensity) at 16, 64, 256.
PERIODS = {
    0: ((1, 0.0000, 0, 0.0000, 0.0000), (1, 0.0000, 0, 0.0000, 0.0000), (1, 0.0000, 0, 0.0000, 0.0000)),
    1: ((55, 0.9600, 1, 0.0400, 0.6397), (57, 0.9949, 1, 0.0051, 0.3246), (172, 3.0022, 3, 0.0022, 0.5735)),
    2: ((29, 1.0127, 1, 0.0127, 0.2031), (57, 1.9905, 2, 0.0095, 0.6104), (86, 3.0032, 3, 0.0032, 0.8077)),
    3: ((19, 0.9957, 1, 0.0043, 0.0682), (57, 2.9872, 3, 0.0128, 0.8184), (229, 12.0013, 12, 0.0013, 0.3218)),
    4: ((43, 3.0068, 3, 0.0068, 0.1091), (57, 3.9858, 4, 0.0142, 0.9097), (143, 9.9994, 10, 0.0006, 0.1460)),
    5: ((23, 2.0122, 2, 0.0122, 0.1955), (57, 4.9868, 5, 0.0132, 0.8447), (80, 6.9990, 7, 0.0010, 0.2509)),
    6: ((19, 1.9970, 2, 0.0030, 0.0486), (57, 5.9909, 6, 0.0091, 0.5838), (314, 33.0024, 33, 0.0024, 0.6104)),
    7: ((49, 6.0164, 6, 0.0164, 0.2621), (57, 6.9986, 7, 0.0014, 0.0866), (57, 6.9986, 7, 0.0014, 0.3464)),
    8: ((50, 7.0270, 7, 0.0270, 0.4315), (57, 8.0107, 8, 0.0107, 0.6876), (185, 25.9998, 26, 0.0002, 0.0557)),
    9: ((19, 3.0093, 3, 0.0093, 0.1484), (82, 12.9874, 13, 0.0126, 0.8073), (101, 15.9967, 16, 0.0033, 0.8555)),
    10: ((17, 2.9975, 3, 0.0025, 0.0396), (17, 2.9975, 3, 0.0025, 0.1583), (380, 67.0035, 67, 0.0035, 0.9062)),
    11: ((36, 6.9976, 7, 0.0024, 0.0381), (36, 6.9976, 7, 0.0024, 0.1525), (391, 76.0019, 76, 0.0019, 0.4844)),
    12: ((33, 7.0143, 7, 0.0143, 0.2287), (80, 17.0043, 17, 0.0043, 0.2780), (207, 43.9987, 44, 0.0013, 0.3232)),
    13: ((13, 3.0013, 3, 0.0013, 0.0201), (13, 3.0013, 3, 0.0013, 0.0803), (758, 174.9962, 175, 0.0038, 0.9727)),
    14: ((52, 12.9649, 13, 0.0351, 0.5613), (349, 87.0145, 87, 0.0145, 0.9302), (365, 91.0037, 91, 0.0037, 0.9570)),
    15: ((41, 10.9858, 11, 0.0142, 0.2272), (56, 15.0050, 15, 0.0050, 0.3196), (209, 56.0008, 56, 0.0008, 0.1992)),
    16: ((56, 16.0576, 16, 0.0576, 0.9211), (129, 36.9897, 37, 0.0103, 0.6560), (136, 38.9969, 39, 0.0031, 0.7822)),
    17: ((36, 11.0062, 11, 0.0062, 0.0989), (72, 22.0124, 22, 0.0124, 0.7914), (157, 47.9992, 48, 0.0008, 0.2080)),
    18: ((37, 12.0219, 12, 0.0219, 0.3503), (40, 12.9966, 13, 0.0034, 0.2148), (277, 90.0018, 90, 0.0018, 0.4492)),
    19: ((29, 9.9854, 10, 0.0146, 0.2338), (61, 21.0038, 21, 0.0038, 0.2401), (61, 21.0038, 21, 0.0038, 0.9604)),
    20: ((11, 4.0036, 4, 0.0036, 0.0580), (228, 82.9843, 83, 0.0157, 1.0063), (272, 98.9988, 99, 0.0012, 0.3105)),
    21: ((52, 19.9607, 20, 0.0393, 0.6288), (86, 33.0119, 33, 0.0119, 0.7637), (99, 38.0021, 38, 0.0021, 0.5391)),
    22: ((47, 18.9890, 19, 0.0110, 0.1758), (52, 21.0091, 21, 0.0091, 0.5839), (99, 39.9981, 40, 0.0019, 0.4766)),
    23: ((33, 14.0075, 14, 0.0075, 0.1201), (66, 28.0150, 28, 0.0150, 0.9609), (139, 59.0013, 59, 0.0013, 0.3379)),
    24: ((54, 24.0421, 24, 0.0421, 0.6731), (128, 56.9886, 57, 0.0114, 0.7292), (146, 65.0026, 65, 0.0026, 0.6719)),
    25: ((15, 6.9945, 7, 0.0055, 0.0875), (148, 69.0127, 69, 0.0127, 0.8140), (178, 83.0018, 83, 0.0018, 0.4570)),
    26: ((39, 19.0213, 19, 0.0213, 0.3415), (41, 19.9968, 20, 0.0032, 0.2050), (285, 139.0021, 139, 0.0021, 0.5430)),
    27: ((51, 25.9855, 26, 0.0145, 0.2322), (51, 25.9855, 26, 0.0145, 0.9288), (210, 106.9991, 107, 0.0009, 0.2402)),
    28: ((32, 17.0145, 17, 0.0145, 0.2319), (79, 42.0045, 42, 0.0045, 0.2900), (205, 108.9991, 109, 0.0009, 0.2305)),
    29: ((56, 31.0409, 31, 0.0409, 0.6548), (83, 46.0071, 46, 0.0071, 0.4534), (175, 97.0029, 97, 0.0029, 0.7383)),
    30: ((26, 15.0109, 15, 0.0109, 0.1747), (71, 40.9914, 41, 0.0086, 0.5532), (97, 56.0023, 56, 0.0023, 0.5830)),
    31: ((50, 30.0426, 30, 0.0426, 0.6824), (218, 130.9859, 131, 0.0141, 0.8994), (233, 139.9987, 140, 0.0013, 0.3203)),
    32: ((8, 4.9989, 5, 0.0011, 0.0178), (8, 4.9989, 5, 0.0011, 0.0710), (877, 548.0034, 548, 0.0034, 0.8594)),
    33: ((20, 12.9880, 13, 0.0120, 0.1923), (57, 37.0158, 37, 0.0158, 1.0081), (77, 50.0037, 50, 0.0037, 0.9561)),
    34: ((40, 26.9800, 27, 0.0200, 0.3203), (43, 29.0035, 29, 0.0035, 0.2228), (255, 171.9974, 172, 0.0026, 0.6680)),
    35: ((10, 7.0020, 7, 0.0020, 0.0317), (50, 35.0099, 35, 0.0099, 0.6340), (487, 340.9965, 341, 0.0035, 0.8984)),
    36: ((51, 37.0532, 37, 0.0532, 0.8505), (106, 77.0124, 77, 0.0124, 0.7964), (128, 92.9962, 93, 0.0038, 0.9824)),
    37: ((57, 42.9520, 43, 0.0480, 0.7682), (69, 51.9945, 52, 0.0055, 0.3516), (142, 107.0032, 107, 0.0032, 0.8145)),
    38: ((32, 25.0008, 25, 0.0008, 0.0126), (32, 25.0008, 25, 0.0008, 0.0503), (32, 25.0008, 25, 0.0008, 0.2012)),
    39: ((21, 17.0052, 17, 0.0052, 0.0835), (63, 51.0157, 51, 0.0157, 1.0020), (184, 148.9981, 149, 0.0019, 0.4844)),
    40: ((31, 26.0117, 26, 0.0117, 0.1873), (56, 46.9889, 47, 0.0111, 0.7112), (87, 73.0006, 73, 0.0006, 0.1523)),
    41: ((23, 19.9933, 20, 0.0067, 0.1072), (107, 93.0123, 93, 0.0123, 0.7866), (153, 132.9989, 133, 0.0011, 0.2852)),
    42: ((10, 9.0039, 9, 0.0039, 0.0624), (221, 198.9863, 199, 0.0137, 0.8799), (251, 225.9980, 226, 0.0020, 0.5234)),
    43: ((59, 55.0175, 55, 0.0175, 0.2805), (74, 69.0050, 69, 0.0050, 0.3228), (163, 151.9976, 152, 0.0024, 0.6172)),
    44: ((29, 28.0045, 28, 0.0045, 0.0724), (29, 28.0045, 28, 0.0045, 0.2897), (204, 196.9974, 197, 0.0026, 0.6758)),
    45: ((1, 1.0000, 1, 0.0000, 0.0003), (1, 1.0000, 1, 0.0000, 0.0010), (1, 1.0000, 1, 0.0000, 0.0042)),
}  # fmt: skip
# Table 4-7's printed degree column, i = 0..50 (m = i/50; period and value are 50/gcd, i/gcd).
DEGREES_4_7 = (
    0.000, 1.146, 2.291, 3.434, 4.574, 5.711, 6.843, 7.970, 9.090, 10.204, 11.310, 12.408, 13.496,
    14.574, 15.642, 16.699, 17.745, 18.778, 19.799, 20.807, 21.802, 22.783, 23.750, 24.703, 25.641,
    26.565, 27.475, 28.369, 29.249, 30.114, 30.964, 31.799, 32.620, 33.425, 34.216, 34.992, 35.754,
    36.502, 37.235, 37.955, 38.660, 39.352, 40.031, 40.696, 41.348, 41.988, 42.614, 43.229, 43.831,
    44.422, 45.000,
)  # fmt: skip


def _tie(area, levels):
    """A printed .5 tie: the author's float went either way (spec §0)."""
    return abs(area * (levels - 1) - math.floor(area * (levels - 1)) - 0.5) < 1e-6


def _check_intensities(areas, printed, levels):
    got = intensities(np.clip(areas, 0, 1), levels).tolist()
    for area, value, expected in zip(areas, got, printed, strict=True):
        assert value == expected or (_tie(area, levels) and abs(value - expected) == 1)


def test_table_4_1_all_100_rows():
    """The dxy recurrence from 0 and DISLOP_L's middle formula, 5 degrees, pi = 3.14156."""
    m, dxy = degree_slope(5), 0.0
    for printed_dxy, *row in TABLE_4_1:
        areas = columns.line_column(m, dxy)[:3]
        assert dxy == pytest.approx(printed_dxy, abs=1.5e-4)
        assert areas == pytest.approx(row[:3], abs=1.5e-4)
        _check_intensities(areas, row[3:6], 16)
        _check_intensities(areas, row[6:9], 256)
        dxy += m
        dxy -= 1.0 if dxy > 0.5 else 0.0


@pytest.mark.parametrize("column, levels", [(0, 16), (1, 64), (2, 256)])
def test_tables_4_2_to_4_4_derived_columns_given_the_printed_period(column, levels):
    for degree, rows in PERIODS.items():
        period, value, n, area, precision = rows[column]
        table = periodic_table(degree_slope(degree), levels)
        assert table.period == period == PRINTED_PERIODS[levels][degree]
        assert table.value == pytest.approx(value, abs=1e-4)
        assert table.n == n
        assert table.residual == pytest.approx(area, abs=1e-4)
        assert table.precision == pytest.approx(precision, abs=levels * 1e-4)
        assert table.residual < 1 / (levels - 1)  # every printed period meets the tolerance


def test_period_rule_reproduces_table_4_3_and_counts_for_16_and_64_levels():
    """Smallest p with |m p - n| < 1/L and drift over 60 columns < 1/L; the printed rule is lost."""
    matches = {
        levels: sum(
            period_rule(degree_slope(d), levels) == PRINTED_PERIODS[levels][d] for d in range(1, 45)
        )
        for levels in (16, 64, 256)
    }
    assert matches == {16: 29, 64: 31, 256: 44}
    assert period_rule(0.0, 64) == period_rule(1.0, 64) == 1
    assert printed_period(0.3, 64) is None and printed_period(0.3, 32) is None
    table = periodic_table(0.3, 64)  # not a printed degree: the rule
    assert table.period == period_rule(0.3, 64) and table.residual < 1 / 64


def test_table_4_5_line_5_degrees_64_levels_period_57():
    table = periodic_table(degree_slope(5), 64)
    assert table.period == 57 and table.n == 5 and table.areas.shape == (58, 3)
    printed = {
        0: (-0.5, (0.0, 0.5019, 0.5019), (0, 32, 32)),
        27: (-0.0263, (0.0021, 0.9721, 0.0296), (0, 61, 2)),
        28: (-0.0088, (0.0078, 0.9791, 0.0169), (0, 62, 1)),
        29: (0.0088, (0.0169, 0.9791, 0.0078), (1, 62, 0)),
        57: (0.5, (0.5019, 0.5019, 0.0), (32, 32, 0)),
    }
    for j, (dxy, areas, levels) in printed.items():
        assert table.dxy[j] == pytest.approx(dxy, abs=1e-4)
        assert table.areas[j] == pytest.approx(areas, abs=1e-4)
        assert table.intensities[j].tolist() == list(levels)


def test_table_4_6_top_edge_40_degrees_period_56():
    table = periodic_table(degree_slope(40), 64, kind="edge", flag=1)
    assert table.period == 56 and table.n == 47
    printed = {
        0: ((0.0, 0.1049, 0.8951), (0, 7, 56)),
        23: ((0.0, 0.4108, 1.0), (0, 26, 63)),
        24: ((0.0, 0.4286, 0.0), (0, 27, 0)),  # the one-pixel branch
        34: ((0.0004, 0.6067, 0.0), (0, 38, 0)),
        56: ((0.1049, 0.8951, 0.0), (7, 56, 0)),
    }
    for j, (areas, levels) in printed.items():
        assert table.areas[j] == pytest.approx(areas, abs=1e-4)
        assert table.intensities[j].tolist() == list(levels)
    assert (
        table.areas[28, 1] == pytest.approx(0.5) and table.intensities[28, 1] == 32
    )  # printed 31: a tie


def test_table_4_7_all_51_slopes_have_exact_period_50_over_gcd():
    for i in range(DIVISIONS + 1):
        m = Fraction(i, DIVISIONS)
        period = next(p for p in range(1, 51) if (m * p).denominator == 1)  # the smallest exact one
        assert period == 50 // math.gcd(i, 50)
        assert periodic_table(i / 50, 64, period).residual == pytest.approx(0.0, abs=1e-12)
        assert periodic_table(i / 50, 64, period).n == i // math.gcd(i, 50)
    assert math.lcm(*(50 // math.gcd(i, 50) for i in range(51))) == 50
    error = [DEGREES_4_7[i] - math.degrees(math.atan(i / 50)) for i in range(51)]
    assert (
        max(map(abs, error)) < 8e-4
    )  # 12 printed degrees are 5e-4..8e-4 high (40.031 for 40.0303)
    assert sum(abs(e) < 5e-4 for e in error) == 39


def test_line_table_is_dislop_l_on_the_grid():
    table = line_table()
    assert table.shape == (51, 51, 3) and not table.flags.writeable
    for i, j in [(0, 0), (4, 1), (34, 10), (50, 50), (37, 13)]:
        assert table[i, j].tolist() == list(columns.line_column(i / 50, -0.5 + j / 50)[:3])
    assert np.allclose(table.sum(axis=2), np.sqrt(1 + (np.arange(51) / 50) ** 2)[:, None])


@pytest.mark.parametrize(
    "i, j, areas, levels",
    [
        (4, 0, (0.0, 0.5016, 0.5016), (0, 32, 32)),  # Table 4-8
        (4, 1, (0.0, 0.5216, 0.4816), (0, 33, 30)),
        (4, 24, (0.0029, 0.9766, 0.0237), (0, 62, 1)),
        (4, 25, (0.0108, 0.9816, 0.0108), (1, 62, 1)),
        (4, 50, (0.5016, 0.5016, 0.0), (32, 32, 0)),
        (34, 0, (0.0, 0.6046, 0.6046), (0, 38, 38)),  # Table 5-1
        (34, 10, (0.0154, 0.7893, 0.4046), (1, 50, 25)),
        (34, 11, (0.0199, 0.8047, 0.3846), (1, 51, 24)),
        (34, 25, (0.1454, 0.9185, 0.1454), (9, 58, 9)),
        (34, 50, (0.6046, 0.6046, 0.0), (38, 38, 0)),
    ],
)
def test_tables_4_8_and_5_1_line_slices(i, j, areas, levels):
    assert line_table()[i, j] == pytest.approx(areas, abs=1e-4)
    assert intensities(line_table()[i, j], 64).tolist() == list(levels)


@pytest.mark.parametrize(
    "flag, i, j, areas, levels",
    [
        (1, 42, 0, (0.0, 0.1050, 0.8950), (0, 7, 56)),  # Table 4-9
        (1, 42, 22, (0.0, 0.4400, 0.0), (0, 28, 0)),
        (1, 42, 30, (0.0002, 0.5998, 0.0), (0, 38, 0)),
        (1, 42, 50, (0.1050, 0.8950, 0.0), (7, 56, 0)),
        (0, 34, 0, (0.0, 0.9150, 0.0850), (0, 58, 5)),  # Table 5-3
        (0, 34, 17, (0.0, 0.6600, 0.0), (0, 42, 0)),
        (0, 34, 50, (0.9150, 0.0850, 0.0), (58, 5, 0)),
        (1, 34, 0, (0.0, 0.0850, 0.9150), (0, 5, 58)),  # Table 5-4
        (1, 34, 33, (0.0, 0.6600, 0.0), (0, 42, 0)),
        (1, 34, 50, (0.0850, 0.9150, 0.0), (5, 58, 0)),
    ],
)
def test_tables_4_9_5_3_5_4_edge_slices(flag, i, j, areas, levels):
    assert edge_tables()[flag, i, j] == pytest.approx(areas, abs=1e-4)
    assert intensities(edge_tables()[flag, i, j], 64).tolist() == list(levels)


def test_table_4_9_ties_and_the_cv_zero_boundary():
    """Three .5 ties: scanviz's floats give 13, 62, 50 where the print has 14, 61, 49.

    At j = 21 (dxy = -0.08, cv = 0) the formula takes the two-pixel branch, as printed.
    """
    table = edge_tables()[1, 42]
    assert table[9, 1] * 63 == pytest.approx(13.5) and intensities(table[9, 1]) == 13  # printed 14
    assert (
        table[11, 2] * 63 == pytest.approx(61.5) and intensities(table[11, 2]) == 62
    )  # printed 61
    assert (
        table[41, 1] * 63 == pytest.approx(49.5) and intensities(table[41, 1]) == 50
    )  # printed 49
    assert table[21].tolist() == pytest.approx([0.0, 0.42, 1.0])  # printed 0.0000 0.4200 1.0000


def test_tables_5_3_5_4_cv_zero_entries_differ_from_print_only_in_the_neighbour():
    """m = 0.68, dxy = +-0.16: cv = 0; the formula reports the neighbour as 1, the print as 0."""
    flag0, flag1 = edge_tables()[0, 34], edge_tables()[1, 34]
    assert columns.edge_column(0.68, 0.16, 0)[3] == pytest.approx(0.0, abs=1e-12)
    assert flag0[33].tolist() == pytest.approx([1.0, 0.34, 0.0])  # printed 0.0000 0.3400 0.0000
    assert flag1[17].tolist() == pytest.approx([0.0, 0.34, 1.0])  # printed 0.0000 0.3400 0.0000
    both = edge_tables()[0] + edge_tables()[1]  # the two sides of an edge complement each other
    assert np.allclose(both[:, :, 1], 1.0)
    assert np.allclose(both[:, :, [0, 2]][both[:, :, [0, 2]] != 0], 1.0)


def test_indices_of_the_worked_examples():
    assert (slope_index(0.080), slope_index(0.0875), slope_index(0.6747)) == (4, 4, 34)
    assert slope_index(-0.6747) == 34 and slope_index(1.0) == 50
    assert (distance_index(-0.5), distance_index(-0.0024), distance_index(0.5)) == (0, 25, 50)


def test_figure_5_2_exact_and_simple_indices():
    p0, p1 = (100.8, 150.7), (109.1, 156.3)  # the dissertation's (100.3, 150.2)-(108.6, 155.8)
    exact, simple = column_indices(p0, p1), column_indices(p0, p1, "simple")
    assert exact.i == simple.i == 34 and exact.m == pytest.approx(0.6747, abs=1e-4)
    assert exact.x[:9].tolist() == list(range(100, 109)) and exact.x[-1] == 109
    assert exact.j[:9].tolist() == [25, 9, 42, 26, 10, 44, 27, 11, 45]
    assert simple.j[:9].tolist() == [25, 9, 43, 27, 11, 45, 29, 13, 47]
    printed = [-0.0024, -0.3277, 0.3470, 0.0217, -0.3036, 0.3711, 0.0458, -0.2795, 0.3952]
    assert exact.dxy[:9] == pytest.approx(printed, abs=1e-4)
    assert exact.iy[0] == 150 and np.all(np.diff(exact.iy) >= 0)


def test_figure_5_2_exact_indices_are_closer_to_figure_5_1():
    """Column 104 (#4): areas 0.013888, 0.785659, 0.406778; j = 10 is closer than j = 11."""
    fig = np.array([0.013888, 0.785659, 0.406778])
    exact, simple = line_table()[34, 10], line_table()[34, 11]
    assert np.abs(exact - fig).max() < np.abs(simple - fig).max()


def test_column_indices_match_direct_evaluation_and_octants():
    rng = np.random.default_rng(4)
    for p0, p1 in rng.uniform(-20, 80, (40, 2, 2)):
        got = column_indices(p0, p1)
        u0, v0 = (p0[1], p0[0]) if got.steep else (p0[0], p0[1])
        u1 = p1[1] if got.steep else p1[0]
        u0, u1 = sorted((u0 - 0.5, u1 - 0.5))
        assert got.x[0] == math.floor(u0 + 0.5) and got.x[-1] == math.floor(u1 + 0.5)
        assert np.all((got.dxy > -0.5) & (got.dxy <= 0.5))
        assert 0 <= got.m <= 1 and got.i == slope_index(got.m)
    flat = column_indices((0, 0), (0, 0))
    assert flat.x.tolist() == [0] and flat.m == 0.0


@njit(cache=True)
def _worst_line_error(table, n, exact_band):
    worst = 0.0
    for a in range(n + 1):
        m = a / n
        i = int(m * 50 + 0.5)
        for b in range(1, n + 1):
            dxy = -0.5 + b / n
            j = int((dxy + 0.5) * 50 + 0.5)
            up, mid, low, _, _, _ = columns.line_column_compiled(m, dxy)
            if exact_band:
                up = columns.band_row_compiled(m, dxy, 1)
                mid = columns.band_row_compiled(m, dxy, 0)
                low = columns.band_row_compiled(m, dxy, -1)
            for k, value in enumerate((up, mid, low)):
                worst = max(worst, abs(table[i, j, k] - value))
    return worst


@njit(cache=True)
def _worst_edge_error(table, n, flag):
    """Against the exact half-plane area, counting an unreported interior neighbour as 1."""
    worst = 0.0
    for a in range(n + 1):
        m = a / n
        i = int(m * 50 + 0.5)
        for b in range(1, n + 1):
            dxy = -0.5 + b / n
            j = int((dxy + 0.5) * 50 + 0.5)
            for k in range(3):
                below = columns.ramp_mean_compiled(dxy - (1 - k) + 0.5, m)
                exact = below if flag == 1 else 1.0 - below
                value = table[i, j, k]
                if value == 0.0 and k == (2 if flag == 1 else 0):
                    value = 1.0
                worst = max(worst, abs(value - exact))
    return worst


def test_worst_area_error_of_the_lookup():
    """The spec's 0.0135 (< 1/63) over all m, dxy: measured on a 2000 x 2000 grid."""
    worst = _worst_line_error(line_table(), 2000, False)
    assert worst == pytest.approx(0.013527, abs=1e-6)
    assert worst < 1 / 63
    assert _worst_line_error(line_table(), 2000, True) == pytest.approx(0.031487, abs=1e-6)
    for flag in (0, 1):
        assert _worst_edge_error(edge_tables()[flag], 2000, flag) == pytest.approx(0.01, abs=1e-9)


def test_lookup_intensities_within_one_level_of_direct():
    """§4.8: Table 4-5 against the i = 4 slice, Table 4-6 against the i = 42 slice."""
    for table, lut in [
        (periodic_table(degree_slope(5), 64), line_table()[4]),
        (periodic_table(degree_slope(40), 64, kind="edge"), edge_tables()[1, 42]),
    ]:
        j = np.array([distance_index(float(d)) for d in table.dxy])
        direct = table.areas.copy()
        looked = lut[j].copy()
        if lut is not line_table()[4]:  # effective coverage: the unreported inside pixel is 1
            direct[direct[:, 2] == 0, 2] = 1.0
            looked[looked[:, 2] == 0, 2] = 1.0
        diff = np.abs(intensities(np.clip(looked, 0, 1)).astype(int) - intensities(direct))
        assert diff.max() == 1


@pytest.mark.parametrize(
    "call, error, words",
    [
        (lambda: slope_index(1.5), ValueError, "'m'"),
        (lambda: slope_index(math.nan), ValueError, "'m'"),
        (lambda: slope_index("0.3"), TypeError, "'m'"),
        (lambda: distance_index(0.7), ValueError, "'dxy'"),
        (lambda: intensities([0.5], 1), ValueError, "'levels'"),
        (lambda: intensities([1.5]), ValueError, "'areas'"),
        (lambda: periodic_table(0.3, 64, 0), ValueError, "'period'"),
        (lambda: periodic_table(0.3, 64, 2.5), TypeError, "'period'"),
        (lambda: periodic_table(0.3, 64, kind="circle"), ValueError, "'kind'"),
        (lambda: periodic_table(0.3, 64, kind="edge", flag=2), ValueError, "'flag'"),
        (lambda: period_rule(1e-9, 64), ValueError, "'m'"),
        (lambda: column_indices((0, 0), (1, math.inf)), ValueError, "'p1'"),
        (lambda: column_indices((0, 0), (1, 1), "fast"), ValueError, "'recurrence'"),
    ],
)
def test_bad_input_names_the_argument(call, error, words):
    with pytest.raises(error, match=words):
        call()

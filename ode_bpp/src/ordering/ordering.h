// Everything of the ordering step in one include: graphs, Cuthill-McKee, row orders.
#pragma once

#include "ordering/cuthill_mckee.h"
#include "ordering/graph.h"
#include "ordering/order_rows.h"
